// The implicit integrators through the factory and the parameter file, and
// forced failures (a huge step with one Newton iteration, a step-size
// collapse): the run ends with status "unstable" and a clear message, not an
// abort.
#include <deal.II/base/parameter_handler.h>

#include <estep/implicit/implicit_integrator.h>
#include <estep/implicit/implicit_parameters.h>
#include <estep/time_integration/integrator_registry.h>

#include <gtest/gtest.h>

#include "implicit_test_support.h"

#include <sstream>
#include <stdexcept>
#include <string>

namespace
{
  const estep::ElasticBodyWithHessian &
  tiny_cube()
  {
    static const auto body = estep_test::cube_with_hessian(1);
    return *body;
  }

  /** The implicit integrator @p method from @p prm (parse()) with the time
   * step @p dt, as the registry builds it. */
  std::unique_ptr<estep::TimeIntegrator>
  create(const std::string             &method,
         dealii::ParameterHandler      &prm,
         const estep::MechanicalSystem &system,
         const double                   dt)
  {
    prm.enter_subsection("Time integration");
    prm.set("Method", method);
    prm.enter_subsection("Implicit integrators");
    prm.set("Time step", dt);
    prm.leave_subsection();
    std::unique_ptr<estep::TimeIntegrator> integrator;
    try
      {
        integrator = estep::integrator_registry()
                       .get(method, "Time integration/Method")
                       .create(prm, system);
      }
    catch (...)
      {
        prm.leave_subsection();
        throw;
      }
    prm.leave_subsection();
    return integrator;
  }

  /** A ParameterHandler with the subsection Time integration (its Method,
   * the run's span and the implicit subsection), and @p text parsed inside
   * it. */
  void
  parse(dealii::ParameterHandler &prm, const std::string &text)
  {
    prm.enter_subsection("Time integration");
    prm.declare_entry("Method", "ida bdf");
    prm.declare_entry("Start time", "0");
    prm.declare_entry("End time", "1");
    estep::declare_implicit_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string("subsection Time integration\n" + text +
                                "end\n");
  }

  TEST(ImplicitParameters, DefaultsAndParsing)
  {
    dealii::ParameterHandler prm;
    parse(prm,
          "subsection Implicit integrators\n"
          "  set Maximum BDF order = 3\n"
          "  set Linear solver = cg amg\n"
          "  set Newton tolerance = 1e-9\n"
          "end\n");
    prm.enter_subsection("Time integration");
    const estep::ImplicitParameters p = estep::parse_implicit_parameters(prm);
    prm.leave_subsection();
    EXPECT_EQ(p.maximum_bdf_order, 3u);
    EXPECT_EQ(p.linear_solver, estep::ImplicitLinearSolver::cg_amg);
    EXPECT_EQ(p.newton_tolerance, 1e-9);
    EXPECT_EQ(p.relative_tolerance,
              estep::ImplicitParameters().relative_tolerance);
  }

  TEST(ImplicitParameters, OutOfBoundsRejected)
  {
    dealii::ParameterHandler prm;
    EXPECT_ANY_THROW(parse(prm,
                           "subsection Implicit integrators\n"
                           "  set Maximum BDF order = 6\n"
                           "end\n"));
  }

  TEST(CreateImplicitIntegrator, EveryMethodByName)
  {
    dealii::ParameterHandler prm;
    parse(prm, "");
    for (const std::string method :
         {"ida bdf", "arkode midpoint", "arkode irk", "energy momentum"})
      {
        const auto integrator = create(method, prm, tiny_cube(), 0.1);
        EXPECT_EQ(integrator->name(), method);
        const auto run = estep_test::run_cube(tiny_cube(), *integrator, 1.);
        EXPECT_EQ(run.result.status, estep::RunStatus::completed)
          << method << ": " << run.result.message;
        EXPECT_DOUBLE_EQ(integrator->time(), 1.);
        EXPECT_GT(estep_test::counter(run.counters, "newton iterations"), 0u);
        EXPECT_GT(estep_test::counter(run.counters, "jacobian setups"), 0u);
      }
  }

  TEST(CreateImplicitIntegrator, WarnsOfTheEntriesItDoesNotRead)
  {
    dealii::ParameterHandler prm;
    parse(prm,
          "subsection Implicit integrators\n"
          "  set ARKode order = 4\n"
          "  set Minimum step = 1e-9\n"
          "  set Linear tolerance = 1e-8\n"
          "end\n");
    const std::string section = "Time integration/Implicit integrators/";
    EXPECT_EQ(
      create("ida bdf", prm, tiny_cube(), 0.1)->warnings(),
      (std::vector<std::string>{
        section + "ARKode order: Time integration/Method = ida bdf does not "
                  "read it (arkode irk does); it is ignored.",
        section + "Linear tolerance: " + section +
          "Linear solver = direct does not read it (cg amg does); it is "
          "ignored."}));
    // arkode irk reads the first two; energy momentum neither.
    EXPECT_EQ(create("arkode irk", prm, tiny_cube(), 0.1)->warnings().size(),
              1u);
    EXPECT_EQ(
      create("energy momentum", prm, tiny_cube(), 0.1)->warnings().size(), 3u);
    // CG reads the linear tolerance.
    prm.enter_subsection("Time integration");
    prm.enter_subsection("Implicit integrators");
    prm.set("Linear solver", "cg amg");
    prm.leave_subsection();
    prm.leave_subsection();
    EXPECT_TRUE(
      create("arkode irk", prm, tiny_cube(), 0.1)->warnings().empty());
  }

  TEST(CreateImplicitIntegrator, ClearErrors)
  {
    dealii::ParameterHandler prm;
    parse(prm, "");
    try
      {
        create("bdf9", prm, tiny_cube(), 0.1);
        FAIL() << "no exception";
      }
    catch (const std::runtime_error &e)
      {
        EXPECT_NE(std::string(e.what()).find("there is no time integrator"),
                  std::string::npos);
      }
    // A system without a Hessian: a plain ElasticBody.
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, 1);
    const estep::ElasticBody plain(
      tria, std::make_shared<estep::NeoHookean>(0.01, 0.0066), 0.1);
    try
      {
        create("ida bdf", prm, plain, 0.1);
        FAIL() << "no exception";
      }
    catch (const std::invalid_argument &e)
      {
        EXPECT_NE(std::string(e.what()).find("Hessian"), std::string::npos);
      }
  }

  /** Run @p method with a huge step and one Newton iteration. */
  estep::TimeLoopResult
  forced_failure(const std::string &method, const std::string &extra)
  {
    dealii::ParameterHandler prm;
    parse(prm,
          "subsection Implicit integrators\n"
          "  set Maximum Newton iterations = 1\n" +
            extra + "end\n");
    const auto integrator = create(method, prm, tiny_cube(), 5.);
    const auto result =
      estep_test::run_cube(tiny_cube(), *integrator, 20.).result;
    testing::Test::RecordProperty("message", result.message);
    return result;
  }

  TEST(ForcedFailure, ArkodeMidpointNewton)
  {
    const auto result = forced_failure("arkode midpoint", "");
    EXPECT_EQ(result.status, estep::RunStatus::unstable);
    EXPECT_NE(result.message.find("arkode midpoint failed at t = 0"),
              std::string::npos)
      << result.message;
    EXPECT_NE(result.message.find("Newton iteration did not converge"),
              std::string::npos)
      << result.message;
  }

  TEST(ForcedFailure, EnergyMomentumNewton)
  {
    const auto result = forced_failure("energy momentum", "");
    EXPECT_EQ(result.status, estep::RunStatus::unstable);
    EXPECT_NE(result.message.find("energy momentum failed at t = 0"),
              std::string::npos)
      << result.message;
    EXPECT_NE(result.message.find("did not converge in 1 iterations"),
              std::string::npos)
      << result.message;
    // Times and steps as numbers of any size (not "5.000000").
    EXPECT_NE(result.message.find("(step 5)"), std::string::npos)
      << result.message;
  }

  // At a tiny step the Newton tolerance lies below the residual's own
  // round-off, 16 eps (2/dt) max |q|: the method meets the round-off instead of
  // failing at its first step (it did, with dt = 1e-6 on the 8^3 cube).
  TEST(EnergyMomentum, TinyStepsStopAtTheRoundOff)
  {
    dealii::ParameterHandler prm;
    parse(prm, "subsection Implicit integrators\nend\n");
    const auto integrator = create("energy momentum", prm, tiny_cube(), 1e-9);
    const auto run = estep_test::run_cube(tiny_cube(), *integrator, 1e-8);
    EXPECT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_EQ(integrator->n_steps(), 10u);
    EXPECT_LT(std::abs(run.energy_drift), 1e-10);
  }

  TEST(ForcedFailure, IdaStepCollapse)
  {
    const auto result = forced_failure("ida bdf",
                                       "  set Minimum step = 1\n"
                                       "  set Relative tolerance = 1e-12\n"
                                       "  set Absolute tolerance = 1e-14\n");
    EXPECT_EQ(result.status, estep::RunStatus::unstable);
    EXPECT_NE(result.message.find("ida bdf failed at t = "), std::string::npos)
      << result.message;
  }

  TEST(ForcedFailure, ArkodeIrkStepCollapse)
  {
    const auto result = forced_failure("arkode irk",
                                       "  set Minimum step = 1\n"
                                       "  set Relative tolerance = 1e-12\n"
                                       "  set Absolute tolerance = 1e-14\n");
    EXPECT_EQ(result.status, estep::RunStatus::unstable);
    EXPECT_NE(result.message.find("arkode irk failed at t = "),
              std::string::npos)
      << result.message;
  }

  TEST(ForcedFailure, IsAnImplicitSolverFailure)
  {
    dealii::ParameterHandler prm;
    parse(prm,
          "subsection Implicit integrators\n"
          "  set Maximum Newton iterations = 1\n"
          "end\n");
    const auto integrator  = create("energy momentum", prm, tiny_cube(), 5.);
    const estep::Vector q0 = tiny_cube().reference_configuration();
    integrator->initialize(0.,
                           q0,
                           tiny_cube().rigid_velocity(q0,
                                                      {{0., 0., 0.}},
                                                      {{0., 0., 1.}},
                                                      {{0.5, 0.5, 0.5}}));
    EXPECT_THROW(integrator->step(20.), estep::ImplicitSolverFailure);
  }
} // namespace
