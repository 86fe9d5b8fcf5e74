// The check every material passes when it is created from the input
// (parse_material_parameters()): each of the mistakes a material of one's
// own can make is refused, naming the material, the stretch and the function.

#include <deal.II/base/parameter_handler.h>

#include <estep/materials/material_registry.h>
#include <estep/materials/neo_hookean.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace
{
  using estep::Interval;

  /** The neo-Hookean material with one of its functions made wrong by
   * `Mistake`. */
  class FaultyMaterial : public estep::NeoHookean
  {
  public:
    explicit FaultyMaterial(const std::string &mistake)
      : NeoHookean(0.01, 0.0066)
      , mistake(mistake)
    {}

    std::string
    name() const override
    {
      return "faulty";
    }

    // "stress": f(J) - c J, with its derivative and ranges, so that f'(1) =
    // -2 c.
    double
    volumetric_energy(const double J) const override
    {
      const double f = NeoHookean::volumetric_energy(J);
      return mistake == "stress" ? f - 0.0066 * J : f;
    }

    double
    volumetric_derivative(const double J) const override
    {
      const double df = NeoHookean::volumetric_derivative(J);
      if (mistake == "derivative")
        return df + 0.01 * std::log(J); // the lambda term twice
      if (mistake == "stress")
        return df - 0.0066; // f'(1) = -2 c
      if (mistake == "not finite" && J > 1.1)
        return std::numeric_limits<double>::quiet_NaN();
      return df;
    }

    double
    volumetric_second_derivative(const double J) const override
    {
      const double d2f = NeoHookean::volumetric_second_derivative(J);
      return mistake == "second derivative" ? 2. * d2f : d2f;
    }

    Interval
    volumetric_energy_range(const Interval &J) const override
    {
      if (mistake == "energy range") // the midpoint's value only
        return Interval::point(volumetric_energy(0.5 * (J.lower + J.upper)));
      const Interval range = NeoHookean::volumetric_energy_range(J);
      if (mistake == "stress")
        return {range.lower - 0.0066 * J.upper, range.upper - 0.0066 * J.lower};
      return range;
    }

    Interval
    volumetric_derivative_range(const Interval &J) const override
    {
      if (mistake == "derivative range") // the value at the lower end
        return Interval::point(volumetric_derivative(J.lower));
      const Interval range = NeoHookean::volumetric_derivative_range(J);
      if (mistake == "stress")
        return {range.lower - 0.0066, range.upper - 0.0066};
      return range;
    }

  private:
    const std::string mistake;
  };

  void
  declare_faulty(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Faulty");
    prm.declare_entry("Mistake", "none");
    prm.leave_subsection();
  }

  std::shared_ptr<const estep::Material>
  create_faulty(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Faulty");
    const std::string mistake = prm.get("Mistake");
    prm.leave_subsection();
    return std::make_shared<FaultyMaterial>(mistake);
  }
} // namespace

ESTEP_REGISTER_MATERIAL("faulty",
                        "the neo-Hookean material with a mistake (test).",
                        declare_faulty,
                        create_faulty)

namespace
{
  /** The error parse_material_parameters() throws for the faulty material
   * with @p mistake, or "" if it accepts it. */
  std::string
  error_for(const std::string &mistake)
  {
    dealii::ParameterHandler prm;
    prm.enter_subsection("Material");
    estep::declare_material_parameters(prm);
    prm.set("Model", "faulty");
    prm.enter_subsection("Faulty");
    prm.set("Mistake", mistake);
    prm.leave_subsection();
    try
      {
        estep::parse_material_parameters(prm, "Material");
      }
    catch (const std::runtime_error &error)
      {
        return error.what();
      }
    return "";
  }

  void
  expect_error(const std::string &mistake, const std::string &expected)
  {
    const std::string error = error_for(mistake);
    EXPECT_EQ(error.rfind("Material/Model = faulty: at J = ", 0), 0u)
      << mistake << ": " << error;
    EXPECT_NE(error.find(expected), std::string::npos)
      << mistake << ": " << error;
  }
} // namespace

TEST(MaterialCheck, TheShippedMaterialsPass)
{
  EXPECT_EQ(error_for("none"), "");
  for (const auto &plugin : estep::material_registry().plugins())
    if (const std::string model = plugin.name; model != "faulty")
      {
        dealii::ParameterHandler prm;
        prm.enter_subsection("Material");
        estep::declare_material_parameters(prm);
        prm.set("Model", model);
        EXPECT_NO_THROW(estep::parse_material_parameters(prm, "Material"))
          << model;
      }
}

TEST(MaterialCheck, EachMistakeIsNamed)
{
  expect_error("derivative", "f' is not the derivative of f");
  expect_error("second derivative", "f'' is not the derivative of f'");
  expect_error("energy range", "volumetric_energy_range() over [");
  expect_error("derivative range", "volumetric_derivative_range() over [");
  expect_error("stress", "the reference state is not stress-free");
  expect_error("not finite", "f, f' and f'' are not all finite");
}
