#ifndef estep_materials_material_registry_h
#define estep_materials_material_registry_h

#include <estep/base/plugin_registry.h>
#include <estep/materials/material.h>

#include <memory>
#include <string>

namespace estep
{
  /**
   * The create function of a material plugin: reads the material's own
   * parameters (declared by its declare_parameters in the same subsection) and
   * returns the material. Throws std::runtime_error naming the entry on bad
   * values.
   */
  using MaterialFactory =
    std::shared_ptr<const Material>(dealii::ParameterHandler &);

  /** The registered materials. */
  PluginRegistry<MaterialFactory> &
  material_registry();

  /**
   * Declare, in the current subsection of @p prm, how a body's material is
   * chosen: `Model` (a Selection of the registered materials), `Density`, and
   * every registered material's own parameters (each material declares them in
   * a subsection of its own).
   */
  void
  declare_material_parameters(dealii::ParameterHandler &prm);

  /** A material as a Material subsection chooses it. */
  struct MaterialChoice
  {
    std::shared_ptr<const Material> material;
    /** Mass density per unit reference volume (positive). */
    double density;
  };

  /**
   * Read what declare_material_parameters() declared, from the current
   * subsection of @p prm; @p section is that subsection's path for messages
   * ("Material"). Throws std::runtime_error naming the entry on bad values.
   */
  MaterialChoice
  parse_material_parameters(dealii::ParameterHandler &prm,
                            const std::string        &section);

  /** The constants lambda0 >= 0 and mu0 > 0 of a material parametrised by
   * its small-strain Lame constants (the neo-Hookean solids). */
  struct LameConstants
  {
    double lambda;
    double mu;
  };

  /** Declare `Lambda` and `Mu` in the subsection @p section of the current
   * one. */
  void
  declare_lame_constants(dealii::ParameterHandler &prm,
                         const std::string        &section);

  /** Read what declare_lame_constants() declared; throws
   * std::runtime_error unless Mu is positive. */
  LameConstants
  parse_lame_constants(dealii::ParameterHandler &prm,
                       const std::string        &section);
} // namespace estep

/**
 * Register a material: its name (the value of `Model`), a description, the
 * function declaring its parameters and its create function (a
 * MaterialFactory). A material's source file ends with this.
 */
#define ESTEP_REGISTER_MATERIAL(name, description, declare, create) \
  ESTEP_REGISTER_PLUGIN(                                            \
    ::estep::material_registry(), name, description, declare, create)

#endif
