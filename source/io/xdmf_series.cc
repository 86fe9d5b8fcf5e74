#include <estep/io/xdmf_series.h>

#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    std::string
    data_item(const std::size_t  n_rows,
              const unsigned int n_columns,
              const bool         indices,
              const std::string &file_and_path)
    {
      std::ostringstream item;
      item << "<DataItem Dimensions=\"" << n_rows;
      if (n_columns > 1)
        item << ' ' << n_columns;
      item << (indices ? "\" NumberType=\"UInt\" Precision=\"4\"" :
                         "\" NumberType=\"Float\" Precision=\"8\"")
           << " Format=\"HDF\">" << file_and_path << "</DataItem>";
      return item.str();
    }

    const char *
    attribute_type(const unsigned int n_components)
    {
      switch (n_components)
        {
          case 1:
            return "Scalar";
          case 3:
            return "Vector";
          case 9:
            return "Tensor";
          default:
            throw std::logic_error("XdmfSeries: a field of " +
                                   std::to_string(n_components) +
                                   " components");
        }
    }
  } // namespace



  std::string
  XdmfSeries::text(
    const std::vector<std::pair<double, std::string>> &snapshots) const
  {
    std::ostringstream xdmf;
    xdmf << std::setprecision(17) << "<?xml version=\"1.0\" ?>\n"
         << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
         << "<Xdmf Version=\"2.0\">\n  <Domain>\n"
         << "    <Grid Name=\"series\" GridType=\"Collection\" "
            "CollectionType=\"Temporal\">\n";
    for (const auto &[time, snapshot_file] : snapshots)
      {
        std::string indent = "      ";
        if (meshes.size() > 1)
          {
            xdmf << indent
                 << "<Grid Name=\"bodies\" GridType=\"Collection\" "
                    "CollectionType=\"Spatial\">\n"
                 << indent << "  <Time Value=\"" << time << "\"/>\n";
            indent += "  ";
          }
        for (const Mesh &mesh : meshes)
          {
            xdmf << indent << "<Grid Name=\"" << mesh.name
                 << "\" GridType=\"Uniform\">\n";
            if (meshes.size() == 1)
              xdmf << indent << "  <Time Value=\"" << time << "\"/>\n";
            xdmf << indent << "  <Topology TopologyType=\""
                 << (mesh.points_per_cell == 4 ? "Tetrahedron" : "Triangle")
                 << "\" NumberOfElements=\"" << mesh.n_cells << "\">\n"
                 << indent << "    "
                 << data_item(mesh.n_cells,
                              mesh.points_per_cell,
                              true,
                              mesh_file + ":/" + mesh.group + "/cells")
                 << '\n'
                 << indent << "  </Topology>\n"
                 << indent << "  <Geometry GeometryType=\"XYZ\">\n"
                 << indent << "    "
                 << data_item(mesh.n_points,
                              3,
                              false,
                              mesh_file + ":/" + mesh.group + "/points")
                 << '\n'
                 << indent << "  </Geometry>\n";
            if (mesh.has_fields)
              for (const Field &field : fields)
                xdmf << indent << "  <Attribute Name=\"" << field.name
                     << "\" AttributeType=\""
                     << attribute_type(field.n_components) << "\" Center=\""
                     << (field.on_cells ? "Cell" : "Node") << "\">\n"
                     << indent << "    "
                     << data_item(field.on_cells ? mesh.n_cells : mesh.n_points,
                                  field.n_components,
                                  false,
                                  snapshot_file + ":/" + mesh.group + "/" +
                                    field.name)
                     << '\n'
                     << indent << "  </Attribute>\n";
            xdmf << indent << "</Grid>\n";
          }
        if (meshes.size() > 1)
          xdmf << "      </Grid>\n";
      }
    xdmf << "    </Grid>\n  </Domain>\n</Xdmf>\n";
    return xdmf.str();
  }
} // namespace estep
