// Fuzz driver of the gmsh mesh reader as estep uses it: an input is the .msh
// file of a body's mesh (`Mesh/Type = gmsh`, make_mesh(): deal.II's
// GridIn::read_msh, then estep's checks of a tetrahedral mesh) and the .msh
// file of a static surface (read_msh_surface(): a surface mesh of triangles).
#include <deal.II/grid/tria.h>

#include <estep/composite/static_surface.h>
#include <estep/fem/mesh_description.h>

#include "fuzz_support.h"

extern "C" int
LLVMFuzzerInitialize(int *, char ***)
{
  estep_fuzz::initialize();
  return 0;
}



extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, const std::size_t size)
{
  static const std::string file = estep_fuzz::scratch_file("mesh.msh");
  estep_fuzz::write_file(file, data, size);
  try
    {
      estep::MeshDescription description;
      description.type      = "gmsh";
      description.file_name = file;
      dealii::Triangulation<3, 3> tria;
      estep::make_mesh(description, tria);
    }
  catch (const std::exception &error)
    {
      estep_fuzz::check_rejection(error);
    }
  try
    {
      estep::read_msh_surface(file);
    }
  catch (const std::exception &error)
    {
      estep_fuzz::check_rejection(error);
    }
  return 0;
}
