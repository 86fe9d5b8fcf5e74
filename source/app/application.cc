#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/revision.h>
#include <deal.II/base/utilities.h>

#include <estep/app/application.h>
#include <estep/app/ccd_command.h>
#include <estep/app/input_file.h>
#include <estep/app/problem.h>
#include <estep/app/run_parameters.h>
#include <estep/base/config.h>
#include <estep/base/exception_text.h>
#include <estep/composite/contact_system.h>
#include <estep/fem/elastic_body.h>
#include <estep/implicit/create_implicit_integrator.h>
#include <estep/io/contact_monitor.h>
#include <estep/io/field_output.h>
#include <estep/io/history_writer.h>
#include <estep/io/json_writer.h>
#include <estep/io/progress_line.h>
#include <estep/io/progress_log.h>
#include <estep/io/step_histogram.h>
#include <estep/io/trajectory_norm.h>
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/explicit_newmark.h>
#include <estep/time_integration/time_loop.h>

#include <sys/resource.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    const char *usage =
      "Usage: estep [options] INPUT.prm\n"
      "       estep ccd FILE_OR_DIRECTORY...\n"
      "\n"
      "Energy-stepping for nonlinear elastodynamics and particle systems, on deal.II.\n"
      "\n"
      "Options:\n"
      "  -h, --help                     print this help and exit\n"
      "  -v, --version                  print the version and exit\n"
      "  --print-parameters [INPUT]     print every parameter with its documentation and\n"
      "                                 its value (the default, or as INPUT and --set give\n"
      "                                 it) to standard output, and exit; JSON when INPUT\n"
      "                                 is a .json file, PRM otherwise\n"
      "  -s, --set \"Section/Entry=value\" override an entry of INPUT.prm (repeatable);\n"
      "                                 nested subsections are separated by '/'\n"
      "\n"
      "'estep ccd' runs the conservative continuous collision detection on query files\n"
      "(CSV, the format of the Wang et al. sample queries) and prints the counts of\n"
      "queries, positives, false negatives and false positives and the time per query.\n"
      "\n"
      "A run writes the parameters used (parameters.prm), history.csv and summary.json to\n"
      "the directory named by 'set Output directory'.\n"
      "Exit codes: 0 completed, 1 bad input, 2 the run became unstable, 3 the run\n"
      "stalled (its event search could not advance at round-off), 4 an output could\n"
      "not be written (e.g. a full disk), 128 + the signal's number when SIGINT or\n"
      "SIGTERM ended the run (130, 143; summary.json says interrupted).\n";

    /** What the command line asks for. */
    struct CommandLine
    {
      bool        help = false, version = false, print_parameters = false;
      std::string input_file;
      std::vector<std::string> overrides;
    };

    bool
    has_extension(const std::string &name, const std::string &extension)
    {
      return name.size() > extension.size() &&
             name.compare(name.size() - extension.size(),
                          extension.size(),
                          extension) == 0;
    }

    CommandLine
    parse_command_line(int argc, char **argv)
    {
      CommandLine command;
      for (int i = 1; i < argc; ++i)
        {
          const std::string arg = argv[i];
          if (arg == "-h" || arg == "--help")
            command.help = true;
          else if (arg == "-v" || arg == "--version")
            command.version = true;
          else if (arg == "--print-parameters")
            command.print_parameters = true;
          else if (arg == "-s" || arg == "--set")
            {
              if (i + 1 >= argc)
                throw std::runtime_error(
                  "The option " + arg +
                  " needs an argument \"Section/Entry=value\".");
              command.overrides.push_back(argv[++i]);
            }
          else if (arg.rfind("--set=", 0) == 0)
            command.overrides.push_back(arg.substr(6));
          else if (!arg.empty() && arg[0] == '-')
            throw std::runtime_error("Unknown option <" + arg +
                                     ">. See estep --help.");
          else if (command.input_file.empty())
            command.input_file = arg;
          else
            throw std::runtime_error("More than one input file given (<" +
                                     command.input_file + "> and <" + arg +
                                     ">). See estep --help.");
        }
      return command;
    }

    /** Apply one "Section/Sub/Entry=value" override. */
    void
    apply_override(dealii::ParameterHandler &prm, const std::string &text)
    {
      const auto equals = text.find('=');
      if (equals == std::string::npos)
        throw std::runtime_error(
          "--set \"" + text + "\": expected the form \"Section/Entry=value\".");
      const std::string path = dealii::Utilities::trim(text.substr(0, equals));
      const std::string value =
        dealii::Utilities::trim(text.substr(equals + 1));
      std::vector<std::string> sections =
        dealii::Utilities::split_string_list(path, '/');
      if (sections.empty() || sections.back().empty())
        throw std::runtime_error("--set \"" + text + "\": no entry name.");
      const std::string entry = sections.back();
      sections.pop_back();
      if (!sections.empty() && !prm.subsection_path_exists(sections))
        throw std::runtime_error("--set \"" + text +
                                 "\": there is no subsection <" +
                                 path.substr(0, path.rfind('/')) + ">.");
      for (const std::string &section : sections)
        prm.enter_subsection(section);
      try
        {
          prm.set(entry, value);
        }
      catch (const dealii::ExceptionBase &exception)
        {
          for (unsigned int i = 0; i < sections.size(); ++i)
            prm.leave_subsection();
          throw std::runtime_error("--set \"" + text +
                                   "\": " + one_line_message(exception));
        }
      for (unsigned int i = 0; i < sections.size(); ++i)
        prm.leave_subsection();
    }

    /** Declare every parameter, then read the input file and the overrides, if
     * any. */
    void
    read_parameters(const CommandLine &command, dealii::ParameterHandler &prm)
    {
      RunParameters::declare_parameters(prm);
      declare_problem_parameters(prm);
      if (!command.input_file.empty())
        {
          if (!std::filesystem::is_regular_file(command.input_file))
            throw std::runtime_error("The input file <" + command.input_file +
                                     "> does not exist or is not a file.");
          if (!has_extension(command.input_file, ".prm") &&
              !has_extension(command.input_file, ".json") &&
              !has_extension(command.input_file, ".xml"))
            throw std::runtime_error("The input file <" + command.input_file +
                                     "> must end in .prm, .json or .xml.");
          read_input_file(prm, command.input_file);
        }
      for (const std::string &text : command.overrides)
        apply_override(prm, text);
    }

    std::unique_ptr<TimeIntegrator>
    create_integrator(const RunParameters      &parameters,
                      dealii::ParameterHandler &prm,
                      const MechanicalSystem   &system)
    {
      if (parameters.method == "energy stepping")
        return std::make_unique<EnergyStepping>(system,
                                                parameters.energy_step,
                                                parameters.terrace_offset);
      if (parameters.method == "explicit newmark")
        return std::make_unique<ExplicitNewmark>(system, parameters.time_step);
      return create_implicit_integrator(parameters.method,
                                        prm,
                                        system,
                                        parameters.time_step);
    }

    /**
     * Remove what an earlier run left in @p directory that this run might not
     * overwrite, so that nothing there describes another run: field
     * snapshots and their series files, the step histogram, the log. Only
     * estep's own file names are touched.
     */
    void
    remove_earlier_outputs(const std::filesystem::path &directory)
    {
      for (const char *name :
           {"solution.pvd", "solution.xdmf", "step_histogram.csv", "log.txt"})
        std::filesystem::remove(directory / name);
      const std::filesystem::path fields = directory / "fields";
      if (std::filesystem::is_directory(fields))
        for (const auto &entry : std::filesystem::directory_iterator(fields))
          {
            const std::string name = entry.path().filename().string();
            if (name.rfind("solution-", 0) == 0)
              std::filesystem::remove(entry.path());
          }
    }

    /** The largest resident memory of this process so far, in MiB. */
    double
    peak_memory_mib()
    {
      rusage usage;
      getrusage(RUSAGE_SELF, &usage);
      return usage.ru_maxrss / 1024.; // Linux reports KiB
    }

    /** Input errors that only show in the initial state (e.g. a velocity
     * function that evaluates to NaN). */
    void
    check_initial_state(const Problem &problem)
    {
      for (unsigned int i = 0; i < problem.q0.size(); ++i)
        if (!std::isfinite(problem.q0[i]))
          throw std::runtime_error(
            "The initial configuration of the " + problem.system->name() +
            " is not finite (coordinate " + std::to_string(i) +
            "): check its mesh, placement and initial displacement.");
      for (unsigned int i = 0; i < problem.v0.size(); ++i)
        if (!std::isfinite(problem.v0[i]))
          throw std::runtime_error(
            "The initial velocity of the " + problem.system->name() +
            " is not finite (component " + std::to_string(i) +
            "): check its initial velocity entries or function.");
    }

    JsonObject
    momenta_json(const Momenta &m)
    {
      return JsonObject()
        .add("linear", std::vector<double>(m.linear, m.linear + 3))
        .add("angular", std::vector<double>(m.angular, m.angular + 3));
    }

    /** |b - a| relative to |a|, or absolute where a is (numerically) zero. */
    double
    drift(const double a, const double b, const double scale)
    {
      return std::abs(b - a) / (std::abs(a) > 1e-14 * scale ? std::abs(a) : 1.);
    }

    int
    run(const CommandLine &command, int argc, char **argv)
    {
      dealii::ParameterHandler prm;
      read_parameters(command, prm);

      RunParameters parameters;
      parameters.parse_parameters(prm);
      Problem problem = create_problem(prm);
      check_initial_state(problem);

      const MechanicalSystem &system = *problem.system;
      // MPI, where a part needs it: HDF5 output and Trilinos solvers.
      prm.enter_subsection("Implicit integrators");
      const bool trilinos = prm.get("Linear solver") == "cg amg" &&
                            parameters.method != "energy stepping" &&
                            parameters.method != "explicit newmark";
      prm.leave_subsection();
      const bool hdf5 = parameters.field_output_interval > 0. &&
                        parameters.field_output_format == "hdf5";
      std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
      if (trilinos || hdf5)
        mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(argc,
                                                                         argv,
                                                                         1);

      auto integrator = create_integrator(parameters, prm, system);
      integrator->initialize(parameters.start_time, problem.q0, problem.v0);
      const auto *body = dynamic_cast<const ElasticBody *>(&system);
      if (parameters.field_output_interval > 0. && body == nullptr)
        throw std::runtime_error("Output/Field output interval: the system <" +
                                 system.name() + "> has no fields to write.");

      const double T0 =
        kinetic_energy(system, problem.q0.size() ? problem.v0 : Vector());
      const double  V0       = system.energy(problem.q0);
      const Momenta momenta0 = compute_momenta(system, problem.q0, problem.v0);
      if (parameters.method == "energy stepping" &&
          parameters.energy_step > std::abs(T0) + std::abs(V0))
        std::cerr << "estep: warning: Time integration/Energy step: h = "
                  << parameters.energy_step
                  << " exceeds the initial energy scale |T| + |V| = "
                  << std::abs(T0) + std::abs(V0)
                  << " of the system: its terraces are coarser than the "
                     "motion and the results say little.\n";

      // Everything that input can make fail has been done: only now is the
      // output directory touched, first with a summary saying "running", so
      // that no reader takes an earlier run's summary for this one.
      const std::filesystem::path directory(parameters.output_directory);
      const std::string summary_file = (directory / "summary.json").string();
      const auto        status_only  = [&](const std::string &status,
                                   const std::string &message) {
        return JsonObject()
                 .add("estep version", ESTEP_VERSION)
                 .add("status", status)
                 .add("message", message)
                 .add("system", system.name())
                 .add("method", integrator->name())
                 .add("start time", parameters.start_time)
                 .add("end time", parameters.end_time)
                 .to_string() +
               "\n";
      };
      std::filesystem::create_directories(directory);
      write_file_atomically(summary_file, status_only("running", ""));
      remove_earlier_outputs(directory);
      for (const auto &[name, style] :
           {std::pair{"parameters.prm", dealii::ParameterHandler::ShortPRM},
            std::pair{"parameters.json", dealii::ParameterHandler::ShortJSON}})
        {
          std::ostringstream text;
          prm.print_parameters(text, style);
          write_file_atomically((directory / name).string(), text.str());
        }

      std::unique_ptr<HistoryWriter> history;
      try
        {
          history = std::make_unique<HistoryWriter>(
            (directory / "history.csv").string(), *integrator);
        }
      catch (const std::runtime_error &error)
        {
          // The output directory does not take the history (a full disk):
          // the run cannot start.
          try
            {
              write_file_atomically(summary_file,
                                    status_only("failed", error.what()));
            }
          catch (const std::exception &)
            {}
          std::cerr << "estep: " << error.what() << '\n';
          return exit_failed;
        }
      TrajectoryNorm norm;
      StepHistogram  histogram;
      histogram.set_end_time(parameters.end_time);
      std::vector<RunObserver *> observers = {history.get(), &histogram};
      if (parameters.h1_norm)
        observers.push_back(&norm);
      std::unique_ptr<FieldOutput> fields;
      if (parameters.field_output_interval > 0.)
        {
          fields =
            std::make_unique<FieldOutput>(*body,
                                          directory.string(),
                                          hdf5 ? FieldOutput::Format::hdf5 :
                                                 FieldOutput::Format::vtu,
                                          parameters.start_time,
                                          parameters.field_output_interval);
          observers.push_back(fields.get());
        }
      std::unique_ptr<ContactMonitor> contact;
      if (const auto *contact_system =
            dynamic_cast<const ContactSystem *>(&system))
        {
          contact = std::make_unique<ContactMonitor>(*contact_system);
          observers.push_back(contact.get());
        }
      std::unique_ptr<ProgressLine> progress;
      std::unique_ptr<ProgressLog>  log;
      if (parameters.progress != "off")
        {
          const bool terminal =
            parameters.progress == "on" || ProgressLine::stderr_is_terminal();
          if (terminal)
            {
              progress = std::make_unique<ProgressLine>(parameters.start_time,
                                                        parameters.end_time);
              observers.push_back(progress.get());
            }
          log = std::make_unique<ProgressLog>((directory / "log.txt").string(),
                                              parameters.start_time,
                                              parameters.end_time,
                                              parameters.progress_interval,
                                              !terminal);
          observers.push_back(log.get());
        }

      TimeLoopSettings settings;
      settings.start_time      = parameters.start_time;
      settings.end_time        = parameters.end_time;
      settings.output_interval = parameters.history_interval;
      settings.blowup_factor   = parameters.blowup_factor;
      // SIGINT and SIGTERM end the run after the current step, with its
      // summary (status interrupted).
      const auto interrupt = [](const int signal) {
        request_interruption(signal);
      };
      std::signal(SIGINT, interrupt);
      std::signal(SIGTERM, interrupt);
      const TimeLoopResult result =
        run_time_loop(*integrator, settings, observers);
      std::signal(SIGINT, SIG_DFL);
      std::signal(SIGTERM, SIG_DFL);
      progress.reset();
      if (fields && result.status != RunStatus::failed)
        fields->finish();
      if (log && result.status != RunStatus::failed)
        log->finish(*integrator, to_string(result.status));

      // The summary.
      const Vector &q        = integrator->position();
      const Vector &v        = integrator->velocity();
      const double  T1       = kinetic_energy(system, v);
      const double  V1       = system.energy(q);
      const Momenta momenta1 = compute_momenta(system, q, v);
      const double  scale    = std::abs(T0) + std::abs(V0);

      JsonObject summary;
      summary.add("estep version", ESTEP_VERSION)
        .add("status", to_string(result.status))
        .add("message", result.message)
        .add("system", system.name())
        .add("problem", problem.description)
        .add("degrees of freedom", system.n_dofs())
        .add("method", integrator->name())
        .add("start time", parameters.start_time)
        .add("end time", parameters.end_time)
        .add("final time", result.final_time)
        .add("wall seconds", result.wall_seconds)
        .add("peak memory [MiB]", peak_memory_mib());
      JsonObject counters;
      for (const Counter &counter : integrator->counters())
        counters.add(counter.first, counter.second);
      summary.add("counters", counters);
      const double elapsed = result.final_time - parameters.start_time;
      summary
        .add("mean step",
             integrator->n_steps() ? elapsed / integrator->n_steps() : 0.)
        .add("min step", integrator->min_step())
        .add("max step", integrator->max_step());
      JsonObject energies;
      energies.add("initial kinetic", T0)
        .add("initial potential", V0)
        .add("final kinetic", T1)
        .add("final potential", V1)
        .add("total energy drift", drift(T0 + V0, T1 + V1, scale));
      if (const auto *stepping =
            dynamic_cast<const EnergyStepping *>(integrator.get()))
        {
          const double Eh0 = stepping->initial_terraced_energy();
          energies.add("energy step", stepping->energy_step())
            .add("initial terraced energy", Eh0)
            .add("final terraced energy", stepping->terraced_energy())
            .add("terraced energy drift",
                 drift(Eh0, stepping->terraced_energy(), scale));
        }
      summary.add("energies", energies);
      double linear_drift = 0., angular_drift = 0.;
      for (unsigned int c = 0; c < 3; ++c)
        {
          linear_drift =
            std::max(linear_drift,
                     std::abs(momenta1.linear[c] - momenta0.linear[c]));
          angular_drift =
            std::max(angular_drift,
                     std::abs(momenta1.angular[c] - momenta0.angular[c]));
        }
      summary.add("initial momenta", momenta_json(momenta0))
        .add("final momenta", momenta_json(momenta1))
        .add("linear momentum drift", linear_drift)
        .add("angular momentum drift", angular_drift);
      if (parameters.h1_norm)
        summary.add("h1 norm", norm.h1_norm());
      if (contact)
        summary.add("contact", contact->summary(problem.q0, problem.v0, q, v));
      try
        {
          histogram.write((directory / "step_histogram.csv").string());
          write_file_atomically(summary_file, summary.to_string() + "\n");
        }
      catch (const std::exception &error)
        {
          if (result.status != RunStatus::failed)
            throw;
          // The disk that failed the run may not take the summary either.
          std::cerr << "estep: " << error.what() << '\n';
        }

      std::cout << "estep: " << integrator->name() << " on the "
                << system.name() << ": " << to_string(result.status)
                << " at t = " << result.final_time << " after "
                << integrator->n_steps() << " steps in " << result.wall_seconds
                << " s; output in " << directory.string() << "/\n";
      if (contact)
        std::cout << "estep: " << contact->report(problem.q0, problem.v0, q, v)
                  << '\n';
      std::cerr << (result.message.empty() ? "" : "estep: ") << result.message
                << (result.message.empty() ? "" : "\n");
      switch (result.status)
        {
          case RunStatus::completed:
            return exit_success;
          case RunStatus::unstable:
            return exit_unstable;
          case RunStatus::stalled:
            return exit_stalled;
          case RunStatus::failed:
            return exit_failed;
          case RunStatus::interrupted:
            return 128 + result.signal;
        }
      return exit_failed;
    }
  } // namespace



  int
  run_application(int argc, char **argv)
  {
    // deal.II's exceptions reach us as exceptions, not as aborts with a stack
    // trace.
    dealii::deal_II_exceptions::disable_abort_on_exception();
    dealii::deal_II_exceptions::suppress_stacktrace_in_exceptions();
    try
      {
        if (argc >= 2 && std::string(argv[1]) == "ccd")
          {
            if (argc == 2)
              throw std::runtime_error(
                "estep ccd: no query file or directory given.");
            if (std::string(argv[2]) == "--help" ||
                std::string(argv[2]) == "-h")
              {
                std::cout << usage;
                return exit_success;
              }
            return run_ccd_command(std::vector<std::string>(argv + 2,
                                                            argv + argc),
                                   std::cout);
          }
        const CommandLine command = parse_command_line(argc, argv);
        if (command.help)
          {
            std::cout << usage;
            return exit_success;
          }
        if (command.version)
          {
            std::cout << "estep " << ESTEP_VERSION << " (deal.II "
                      << DEAL_II_PACKAGE_VERSION << ")\n";
            return exit_success;
          }
        if (command.print_parameters)
          {
            dealii::ParameterHandler prm;
            read_parameters(command, prm);
            prm.print_parameters(std::cout,
                                 has_extension(command.input_file, ".json") ?
                                   dealii::ParameterHandler::JSON :
                                   dealii::ParameterHandler::PRM);
            return exit_success;
          }
        if (command.input_file.empty())
          throw std::runtime_error(
            "No input file given. Usage: estep [options] INPUT.prm "
            "(see estep --help).");
        return run(command, argc, argv);
      }
    catch (const dealii::ExceptionBase &exception)
      {
        std::cerr << "estep: error: " << one_line_message(exception) << '\n';
      }
    catch (const std::exception &exception)
      {
        std::cerr << "estep: error: " << exception.what() << '\n';
      }
    return exit_input_error;
  }
} // namespace estep
