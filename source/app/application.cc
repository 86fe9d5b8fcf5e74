#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/revision.h>
#include <deal.II/base/utilities.h>

#include <estep/app/application.h>
#include <estep/app/ccd_command.h>
#include <estep/app/input_file.h>
#include <estep/app/renamed_entries.h>
#include <estep/app/run_parameters.h>
#include <estep/base/checksum.h>
#include <estep/base/config.h>
#include <estep/base/distributed_blocks.h>
#include <estep/base/exception_text.h>
#include <estep/base/interruption.h>
#include <estep/base/lanes.h>
#include <estep/base/mpi_session.h>
#include <estep/fem/elastic_bodies.h>
#include <estep/io/checkpoint.h>
#include <estep/io/output_directory_lock.h>
#include <estep/io/postprocessor.h>
#include <estep/io/run_summary.h>
#include <estep/materials/material_registry.h>
#include <estep/problems/problem.h>
#include <estep/systems/mechanical_system.h>
#include <estep/time_integration/integrator_registry.h>
#include <estep/time_integration/time_loop.h>

#include <boost/property_tree/json_parser.hpp>
#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    const char *usage =
      "Usage: estep [options] INPUT.prm\n"
      "       mpirun -np P estep [options] INPUT.prm   (P processes share the cells)\n"
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
      "  --threads N                    run the loops over cells on N threads (the\n"
      "                                 entry Threads; 0: one per core, the default;\n"
      "                                 under mpirun, each process its share of them)\n"
      "  --resume                       continue the run from the checkpoint in its\n"
      "                                 output directory (Output/Checkpoint interval),\n"
      "                                 appending to its outputs; without a checkpoint\n"
      "                                 there, start from the beginning\n"
      "\n"
      "'estep ccd' runs the conservative continuous collision detection on query files\n"
      "(CSV, the format of the Wang et al. sample queries) and prints the counts of\n"
      "queries, positives, false negatives and false positives and the time per query.\n"
      "\n"
      "A run writes the parameters used (parameters.prm), history.csv and summary.json to\n"
      "the directory named by 'set Output directory'.\n"
      "Exit codes: 0 completed, 1 bad input, 2 the run became unstable, 3 the run\n"
      "stalled (its event search could not advance at round-off), 4 the run failed\n"
      "(an output could not be written, e.g. a full disk; or a plugin threw), 5 a\n"
      "body passed into another or into an obstacle (e.g. a penalty too soft to\n"
      "keep them apart), 128 + the signal's number when SIGINT or SIGTERM ended\n"
      "the run (130, 143; summary.json says interrupted).\n";

    /** The usage and the registered plugins, by extension point. */
    void
    print_help(std::ostream &out)
    {
      out << usage << "\nPlugins (choose them by name in the input file):\n"
          << "  Problem/System:              " << problem_registry().names(", ")
          << "\n  Material/Model:              "
          << material_registry().names(", ")
          << "\n  Time integration/Method:     "
          << integrator_registry().names(", ")
          << "\n  Postprocessors/List:         "
          << postprocessor_registry().names(", ")
          << "\nestep --print-parameters documents each of them; "
             "'Additional shared libraries' adds your own.\n";
    }

    /** @p error, with a hint where it rejects a name that is not among the
     * registered plugins of an extension point (its Selection or
     * MultipleSelection pattern lists them): the plugins of a library of
     * one's own need that library loaded. */
    std::string
    with_plugin_hint(const std::string &error)
    {
      for (const std::string &names : {problem_registry().names(),
                                       material_registry().names(),
                                       integrator_registry().names(),
                                       postprocessor_registry().names()})
        if (error.find("Selection " + names + " ]") != std::string::npos)
          return error.substr(0, error.find_last_not_of('.') + 1) +
                 ". A plugin of your own is known by its name once "
                 "'Additional shared libraries' names its library (estep "
                 "--help lists the plugins registered).";
      return error;
    }

    /** The number of processes an MPI launcher (Open MPI's or MPICH's
     * mpirun) started this one among, from its environment (1 without a
     * launcher), and this one's rank among them. */
    std::pair<unsigned int, unsigned int>
    launched_ranks()
    {
      for (const auto &[size, rank] :
           {std::pair{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"},
            std::pair{"PMI_SIZE", "PMI_RANK"}})
        if (const char *n = std::getenv(size))
          {
            const char *r = std::getenv(rank);
            return {std::max(1, std::atoi(n)),
                    r != nullptr ? std::max(0, std::atoi(r)) : 0};
          }
      return {1, 0};
    }

    /**
     * On several MPI ranks, the run shares the cells of its elastic bodies
     * among them: a system without any, or with fewer cells than ranks, is an
     * input error.
     */
    void
    check_distribution(const Problem &problem)
    {
      const unsigned int ranks = rank_count();
      if (ranks == 1)
        return;
      const unsigned long long cells = elastic_cells(*problem.system);
      if (cells == 0)
        throw std::runtime_error(
          "estep was started as " + std::to_string(ranks) +
          " MPI processes, but the " + problem.name +
          " has no elastic body whose cells they could share. Run it as "
          "one process; it uses every core (--threads).");
      if (cells < ranks)
        throw std::runtime_error(
          "estep was started as " + std::to_string(ranks) +
          " MPI processes, more than the " + std::to_string(cells) +
          " cells of the " + problem.name +
          " they would share. Start at most as many processes as cells "
          "(and for a gain, far fewer: see doc/parallel.md).");
    }

    /** What the command line asks for. */
    struct CommandLine
    {
      bool help = false, version = false, print_parameters = false,
           resume = false;
      std::string              input_file;
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
          else if (arg == "--resume")
            command.resume = true;
          else if (arg == "--threads")
            {
              const std::string n = (i + 1 < argc) ? argv[++i] : "";
              if (n.empty() || n.size() > 4 ||
                  n.find_first_not_of("0123456789") != std::string::npos ||
                  std::stoi(n) > 4096)
                throw std::runtime_error(
                  "The option --threads needs a number of threads from 0 to "
                  "4096 (0: one per core), not <" +
                  n + ">.");
              command.overrides.push_back("Threads=" + n);
            }
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
      if (const std::string moved = renamed_entry_message(path); !moved.empty())
        throw std::runtime_error("--set \"" + text + "\": " + moved);
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

    /** Whether @p text is an override of the entry @p path. */
    bool
    overrides_entry(const std::string &text, const std::string &path)
    {
      return dealii::Utilities::trim(text.substr(0, text.find('='))) == path;
    }

    void
    check_input_file(const std::string &name)
    {
      if (!std::filesystem::is_regular_file(name))
        throw std::runtime_error("The input file <" + name +
                                 "> does not exist or is not a file.");
      if (!has_extension(name, ".prm") && !has_extension(name, ".json") &&
          !has_extension(name, ".xml"))
        throw std::runtime_error("The input file <" + name +
                                 "> must end in .prm, .json or .xml.");
    }

    /**
     * Load the libraries named in `Additional shared libraries` (input file
     * and overrides): their static registrations add their plugins before
     * the parameters are declared.
     */
    void
    load_plugin_libraries(const CommandLine &command)
    {
      const std::string        entry = "Additional shared libraries";
      dealii::ParameterHandler first_reading;
      first_reading.declare_entry(
        entry, "", dealii::Patterns::List(dealii::Patterns::FileName()));
      if (!command.input_file.empty())
        read_input_file(first_reading, command.input_file, true);
      for (const std::string &text : command.overrides)
        if (overrides_entry(text, entry))
          apply_override(first_reading, text);
      for (const std::string &library :
           dealii::Utilities::split_string_list(first_reading.get(entry), ','))
        {
          const std::size_t errors_before = plugin_registration_errors().size();
          const std::size_t registrations_before = plugin_registration_count();
          // A library loaded already (named twice) registers nothing again.
          void *const loaded_before =
            dlopen(library.c_str(), RTLD_NOW | RTLD_NOLOAD);
          if (loaded_before != nullptr)
            dlclose(loaded_before);
          if (dlopen(library.c_str(), RTLD_NOW | RTLD_GLOBAL) == nullptr)
            throw std::runtime_error(entry + ": cannot load <" + library +
                                     ">: " + dlerror());
          if (plugin_registration_errors().size() > errors_before)
            throw std::runtime_error(
              entry + ": <" + library +
              ">: " + plugin_registration_errors()[errors_before]);
          if (loaded_before == nullptr &&
              plugin_registration_count() == registrations_before)
            throw std::runtime_error(
              entry + ": <" + library +
              "> registers no plugin (no ESTEP_REGISTER_PROBLEM, _MATERIAL, "
              "_INTEGRATOR or _POSTPROCESSOR in it): is it the library of "
              "your plugins?");
        }
    }

    /**
     * What in @p value a .prm file cannot hold, or an empty string: a run
     * writes its parameters to parameters.prm, which must read back to the
     * same values. A value read from a .json or .xml file or from --set may
     * hold what a .prm line cannot.
     */
    std::string
    prm_obstacle(const std::string &value)
    {
      if (value.find('#') != std::string::npos)
        return "'#' (a comment starts there)";
      for (const char c : value)
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
          return "a line break or a control character";
      if (!value.empty() &&
          (std::isspace(static_cast<unsigned char>(value.front())) ||
           std::isspace(static_cast<unsigned char>(value.back()))))
        return "white space at its ends (a .prm line drops it)";
      if (!value.empty() && value.back() == '\\')
        return "a final backslash (a continued line there)";
      return "";
    }

    /**
     * Throw, naming the entry, if a value of @p prm does not match its
     * pattern or is one that parameters.prm could not give back. @p tree:
     * the entries of the current subsection of @p prm as its JSON print
     * gives them. deal.II's .prm reader skips the pattern of a value that
     * holds a '{' (a variant of MultipleParameterLoop), so each value is set
     * again, which checks it.
     */
    void
    check_values(dealii::ParameterHandler          &prm,
                 const boost::property_tree::ptree &tree,
                 const std::string                 &path)
    {
      for (const auto &[name, child] : tree)
        {
          const std::string entry = path.empty() ? name : path + "/" + name;
          const auto        value = child.get_optional<std::string>("value");
          if (!value)
            {
              prm.enter_subsection(name);
              check_values(prm, child, entry);
              prm.leave_subsection();
              continue;
            }
          try
            {
              prm.set(name, *value);
            }
          catch (const std::exception &)
            {
              throw std::runtime_error(
                entry + ": the value <" + *value + "> does not match " +
                child.get<std::string>("pattern_description") + ".");
            }
          if (const std::string obstacle = prm_obstacle(*value);
              !obstacle.empty())
            throw std::runtime_error(
              entry + ": the value <" + *value + "> holds " + obstacle +
              ", which parameters.prm could not give back.");
        }
    }

    /** Declare every parameter. */
    void
    declare_parameters(dealii::ParameterHandler &prm)
    {
      RunParameters::declare_parameters(prm);
      declare_problem_parameters(prm);
    }

    /**
     * Load the plugin libraries, declare every parameter, then read the input
     * file and the overrides, if any (declare_and_read_parameters()).
     */
    void
    read_parameters(const CommandLine &command, dealii::ParameterHandler &prm)
    {
      if (!command.input_file.empty())
        check_input_file(command.input_file);
      load_plugin_libraries(command);
      declare_and_read_parameters(prm, command.input_file, command.overrides);
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
      if (const double T0 = kinetic_energy(*problem.system, problem.v0);
          !std::isfinite(T0))
        throw std::runtime_error(
          "The initial kinetic energy of the " + problem.system->name() +
          " is not finite (" + std::to_string(T0) +
          "): its initial velocity is too large for double precision.");
      // Before any integrator starts from it, whichever (explicit Newmark
      // would call it unstable, the implicit methods' solvers fail). An
      // inverted cell gives +infinity; NaN is a defect of a material or
      // system (of a user's own, say), as is a gradient that is not finite.
      const double V0 = problem.system->energy(problem.q0);
      if (std::isnan(V0))
        throw std::runtime_error(
          "The potential energy of the " + problem.system->name() +
          " at its initial configuration is NaN: a material or system of your "
          "own computes a NaN there (the built-in ones give +infinity where a "
          "cell inverts).");
      if (!std::isfinite(V0))
        throw std::runtime_error(
          "The initial configuration of the " + problem.system->name() +
          " is inadmissible: its potential energy is not finite (a cell "
          "inverted or flattened, or an atom on another): check its mesh, "
          "placement and initial displacement.");
      Vector g(problem.q0.size());
      problem.system->gradient(problem.q0, g);
      for (unsigned int i = 0; i < g.size(); ++i)
        if (!std::isfinite(g[i]))
          throw std::runtime_error(
            "The gradient of the potential energy of the " +
            problem.system->name() +
            " at its initial configuration is not finite (component " +
            std::to_string(i) +
            "): the forces there exceed double precision (points or atoms "
            "almost on each other), or a material or system of your own "
            "computes no finite derivative there.");
    }

    /** The integrator chosen in `Time integration`, initialised with the
     * problem's initial state; its warnings go to standard error. */
    std::unique_ptr<TimeIntegrator>
    create_initialized_integrator(dealii::ParameterHandler &prm,
                                  const Problem            &problem,
                                  const RunParameters      &parameters)
    {
      prm.enter_subsection("Time integration");
      auto integrator = create_integrator(prm, *problem.system);
      prm.leave_subsection();
      integrator->initialize(parameters.start_time, problem.q0, problem.v0);
      for (const std::string &warning : integrator->warnings())
        std::cerr << ("estep: warning: " + warning + "\n");
      return integrator;
    }

    /** The warnings about the input: the problem's (Problem::warnings), then
     * the settings of the other time integrators and of the postprocessors
     * missing from the List, which the run ignores
     * (ignored_integrator_settings(), ignored_postprocessor_settings()). */
    std::vector<std::string>
    input_warnings(dealii::ParameterHandler &prm, const Problem &problem)
    {
      std::vector<std::string> warnings = problem.warnings;
      const auto               add = [&](const std::vector<std::string> &more) {
        warnings.insert(warnings.end(), more.begin(), more.end());
      };
      prm.enter_subsection("Time integration");
      add(ignored_integrator_settings(prm));
      prm.leave_subsection();
      prm.enter_subsection("Postprocessors");
      add(ignored_postprocessor_settings(prm));
      prm.leave_subsection();
      return warnings;
    }

    /** The postprocessors of `Postprocessors/List`. */
    std::vector<std::unique_ptr<Postprocessor>>
    create_run_postprocessors(dealii::ParameterHandler &prm,
                              const Problem            &problem,
                              const TimeIntegrator     &integrator,
                              const RunParameters      &parameters)
    {
      prm.enter_subsection("Postprocessors");
      auto postprocessors = create_postprocessors(prm,
                                                  {integrator,
                                                   problem.q0,
                                                   problem.v0,
                                                   parameters.output_directory,
                                                   parameters.start_time,
                                                   parameters.end_time});
      prm.leave_subsection();
      return postprocessors;
    }

    /**
     * Remove what an earlier run left in @p directory that this run might not
     * overwrite, so that nothing there describes another run: field
     * snapshots, the meshes, the obstacles and their series files, the step
     * histogram, the log, the checkpoint. Only estep's own file names are
     * touched.
     */
    void
    remove_earlier_outputs(const std::filesystem::path &directory)
    {
      for (const std::string &name : {std::string("solution.pvd"),
                                      std::string("solution.xdmf"),
                                      std::string("step_histogram.csv"),
                                      std::string("log.txt"),
                                      checkpoint_file_name,
                                      checkpoint_file_name + ".part"})
        std::filesystem::remove(directory / name);
      const std::filesystem::path fields = directory / "fields";
      if (std::filesystem::is_directory(fields))
        for (const auto &entry : std::filesystem::directory_iterator(fields))
          {
            const std::string name = entry.path().filename().string();
            if (name.rfind("solution-", 0) == 0 || name == "obstacles.vtu" ||
                name.rfind("mesh.h5", 0) == 0)
              std::filesystem::remove(entry.path());
          }
    }

    /**
     * Everything that input can make fail has been done: only now is the
     * output directory touched, first with a summary saying "running" (so
     * that no reader takes an earlier run's summary for this one), then the
     * parameters as read. A resumed run keeps the earlier outputs it
     * continues. The directory exists: the run made it to lock it.
     */
    void
    prepare_output_directory(const std::filesystem::path    &directory,
                             const dealii::ParameterHandler &prm,
                             const RunRecord                &run,
                             const bool                      resumed)
    {
      write_file_atomically((directory / "summary.json").string(),
                            status_summary(run, "running", "").to_string() +
                              "\n");
      if (!resumed)
        remove_earlier_outputs(directory);
      for (const auto &[name, style] :
           {std::pair{"parameters.prm", dealii::ParameterHandler::ShortPRM},
            std::pair{"parameters.json", dealii::ParameterHandler::ShortJSON}})
        {
          std::ostringstream text;
          prm.print_parameters(text, style);
          write_file_atomically((directory / name).string(), text.str());
        }
    }

    /** An output failed (a full disk): @p message on standard error and, if
     * the disk still takes it, in a summary with status failed. */
    void
    report_output_failure(const std::string &summary_file,
                          const RunRecord   &record,
                          const std::string &message)
    {
      // Through C's stderr, which the other processes do not silence, and in
      // one write, which the launcher's banner of MPI_Abort cannot split.
      std::fputs(("estep: error: " + message + "\n").c_str(), stderr);
      try
        {
          write_file_atomically(
            summary_file,
            status_summary(record, "failed", message).to_string() + "\n");
        }
      catch (const std::exception &)
        {}
    }

    /** The checksum of the problem's initial positions and velocities and
     * of its geometry (what checkpoints compare, besides the parameters). */
    std::uint64_t
    initial_state_checksum(const Problem &problem)
    {
      std::uint64_t sum = empty_checksum;
      for (const Vector *x : {&problem.q0, &problem.v0})
        sum = checksum(x->data(), x->size() * sizeof(double), sum);
      return checksum(&problem.geometry_checksum,
                      sizeof(problem.geometry_checksum),
                      sum);
    }

    /** The PRM text of the parameters (what checkpoints compare). */
    std::string
    parameters_text(const dealii::ParameterHandler &prm)
    {
      std::ostringstream text;
      prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
      return text.str();
    }

    /**
     * While it lives, SIGINT and SIGTERM do not end the process: they ask
     * the time loop to end the run after its current step, with a checkpoint
     * and the summary (status interrupted). It lives from before the output
     * directory is written, so that no signal leaves a summary that says
     * running.
     */
    class InterruptionRequests
    {
    public:
      InterruptionRequests()
      {
        const auto request = [](const int signal) {
          request_interruption(signal);
        };
        std::signal(SIGINT, request);
        std::signal(SIGTERM, request);
      }

      ~InterruptionRequests()
      {
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
      }

      InterruptionRequests(const InterruptionRequests &) = delete;
      InterruptionRequests &
      operator=(const InterruptionRequests &) = delete;
    };

    /** Run the time loop from the start, or from @p resumed_state. */
    TimeLoopResult
    run_or_resume_time_loop(
      TimeIntegrator                                    &integrator,
      const RunParameters                               &parameters,
      const std::string                                 &parameters_as_read,
      const std::uint64_t                                initial_state,
      const std::vector<std::unique_ptr<Postprocessor>> &postprocessors,
      const std::optional<TimeLoopState>                &resumed_state)
    {
      TimeLoopSettings settings;
      settings.start_time              = parameters.start_time;
      settings.end_time                = parameters.end_time;
      settings.output_interval         = parameters.history_interval;
      settings.blowup_factor           = parameters.blowup_factor;
      settings.energy_drift_warning    = parameters.energy_drift_warning;
      settings.checkpoint_interval     = parameters.checkpoint_interval;
      settings.checkpoint_wall_seconds = parameters.checkpoint_wall_seconds;
      // Every rank takes part in a checkpoint (the integrator completes its
      // state), the first writes it.
      if (parameters.checkpoint_interval > 0. ||
          parameters.checkpoint_wall_seconds > 0.)
        settings.write_checkpoint = [&](const TimeLoopState &state) {
          if (this_rank() == 0)
            write_checkpoint((std::filesystem::path(
                                parameters.output_directory) /
                              checkpoint_file_name)
                               .string(),
                             parameters_as_read,
                             initial_state,
                             state,
                             integrator,
                             postprocessors);
        };
      std::vector<RunObserver *> observers;
      for (const auto &postprocessor : postprocessors)
        observers.push_back(postprocessor.get());
      return resumed_state ? resume_time_loop(integrator,
                                              settings,
                                              observers,
                                              *resumed_state) :
                             run_time_loop(integrator, settings, observers);
    }

    /** Let every postprocessor finish; one whose output cannot be written
     * fails the run. */
    void
    finish_postprocessors(
      const std::vector<std::unique_ptr<Postprocessor>> &postprocessors,
      TimeLoopResult                                    &result)
    {
      for (const auto &postprocessor : postprocessors)
        try
          {
            postprocessor->finish(result);
          }
        catch (const std::exception &error)
          {
            if (result.status != RunStatus::failed)
              {
                result.status  = RunStatus::failed;
                result.message = error.what();
              }
          }
    }

    int
    exit_code(const TimeLoopResult &result)
    {
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
          case RunStatus::penetrated:
            return exit_penetrated;
        }
      return exit_failed;
    }

    /** A run: read the parameters, create the problem, the integrator and the
     * postprocessors, run the time loop, write the summary. */
    int
    run(const CommandLine &command)
    {
      dealii::ParameterHandler prm;
      read_parameters(command, prm);
      const std::string parameters_as_read = parameters_text(prm);
      check_same_on_every_rank(checksum(parameters_as_read.data(),
                                        parameters_as_read.size()),
                               "parameters from <" + command.input_file +
                                 "> and the command line");
      RunParameters parameters;
      parameters.parse_parameters(prm);
      // The ranks on one machine share its cores.
      set_thread_count(parameters.threads != 0 ?
                         parameters.threads :
                         std::max(1u,
                                  dealii::MultithreadInfo::n_cores() /
                                    ranks_on_this_machine()));

      const Problem problem = create_problem(prm);
      check_initial_state(problem);
      check_distribution(problem);
      const bool writes_output = this_rank() == 0;
      const auto integrator =
        create_initialized_integrator(prm, problem, parameters);
      const std::vector<std::string> warnings_at_start = integrator->warnings();
      std::vector<std::string>       warnings_about_input =
        input_warnings(prm, problem);
      if (const unsigned int cores = dealii::MultithreadInfo::n_cores();
          parameters.threads > cores)
        warnings_about_input.push_back(
          "Threads: " + std::to_string(parameters.threads) +
          " threads on a machine of " + std::to_string(cores) +
          " cores: at most " + std::to_string(cores) +
          " run at a time, and the loops' extra parts only cost time (the "
          "trajectory is the same on any number).");
      // The other ranks hold the same state: they run only the
      // postprocessors that write a part of their own.
      auto postprocessors =
        create_run_postprocessors(prm, problem, *integrator, parameters);
      RunRecord record{problem,
                       *integrator,
                       postprocessors,
                       parameters.start_time,
                       parameters.end_time,
                       warnings_about_input,
                       std::nullopt};

      const std::filesystem::path directory(parameters.output_directory);
      const std::string   summary_file  = (directory / "summary.json").string();
      const std::uint64_t initial_state = initial_state_checksum(problem);
      // The output directory is this run's from here on: one that another
      // run uses is refused before its checkpoint is read or any of its
      // files is touched.
      std::optional<OutputDirectoryLock> output_lock;
      std::string                        lock_error;
      if (writes_output)
        try
          {
            std::filesystem::create_directories(directory);
            output_lock.emplace(directory);
          }
        catch (const std::filesystem::filesystem_error &error)
          {
            lock_error = "cannot prepare the output directory <" +
                         directory.string() + ">: <" + error.path1().string() +
                         ">: " + error.code().message();
          }
        catch (const std::runtime_error &error)
          {
            lock_error = error.what();
          }
      // Whether a process met an error (collective): each prints its own.
      const auto failed_on_a_rank = [](const std::string &error) {
        if (largest_over_ranks(!error.empty()) == 0)
          return false;
        if (!error.empty())
          std::cerr << ("estep: error: " + error + "\n");
        return true;
      };
      if (failed_on_a_rank(lock_error))
        return exit_failed;
      std::optional<Checkpoint>    checkpoint;
      std::optional<TimeLoopState> resumed_state;
      if (command.resume)
        {
          const std::string file = (directory / checkpoint_file_name).string();
          if (std::filesystem::exists(file))
            checkpoint.emplace(file);
          check_same_on_every_rank(checkpoint ? checkpoint->checksum() : 0,
                                   "checkpoints <" + file + ">");
          if (checkpoint)
            {
              checkpoint->check_parameters(parameters_as_read);
              checkpoint->check_initial_state(initial_state);
              resumed_state            = checkpoint->restore(*integrator);
              record.resumed_from_time = integrator->time();
              if (integrator->time() > parameters.end_time)
                {
                  std::ostringstream message;
                  message << "--resume: Time integration/End time = "
                          << parameters.end_time
                          << " is before the time of the checkpoint <" << file
                          << ">, t = " << integrator->time()
                          << "; a run resumes to its end time or a later one.";
                  throw std::runtime_error(message.str());
                }
              std::cout << "estep: resuming from <" << file
                        << "> at t = " << integrator->time() << " after "
                        << integrator->n_steps() << " steps\n";
            }
          else
            std::cout << "estep: --resume: no checkpoint in "
                      << directory.string()
                      << "/: the run starts from the beginning\n";
        }
      // A resume takes over the outputs before the summary and the
      // parameters are written, so that one which cannot (history.csv cut
      // short) leaves them as they were.
      std::string start_error;
      if (checkpoint)
        try
          {
            checkpoint->resume(postprocessors, !writes_output);
          }
        catch (const std::runtime_error &error)
          {
            start_error = error.what();
          }
      if (failed_on_a_rank(start_error))
        return exit_failed;
      const InterruptionRequests interruption_requests;
      std::string                preparation_error;
      if (writes_output)
        try
          {
            prepare_output_directory(directory,
                                     prm,
                                     record,
                                     checkpoint.has_value());
          }
        catch (const std::filesystem::filesystem_error &error)
          {
            preparation_error =
              "<" + error.path1().string() + ">: " + error.code().message();
          }
        catch (const std::exception &error)
          {
            preparation_error = one_line_message(error);
          }
      if (largest_over_ranks(!preparation_error.empty()) != 0)
        {
          // The summary, if written already, says running: now failed.
          if (!preparation_error.empty())
            report_output_failure(summary_file,
                                  record,
                                  "cannot prepare the output directory <" +
                                    directory.string() +
                                    ">: " + preparation_error);
          return exit_failed;
        }
      try
        {
          if (!writes_output)
            postprocessors.erase(
              std::remove_if(postprocessors.begin(),
                             postprocessors.end(),
                             [](const auto &postprocessor) {
                               return !postprocessor->runs_on_every_rank();
                             }),
              postprocessors.end());
          if (!checkpoint)
            for (const std::size_t i : start_order(postprocessors))
              postprocessors[i]->start();
        }
      catch (const std::runtime_error &error)
        {
          start_error = error.what();
        }
      // The output directory does not take the outputs (a full disk): the
      // run cannot start. The first process says why, whichever failed.
      if (start_error = first_message_over_ranks(start_error);
          !start_error.empty())
        {
          if (writes_output)
            report_output_failure(summary_file, record, start_error);
          return exit_failed;
        }

      // Printed once the run starts, so that a refusal before stays one line.
      if (writes_output)
        for (const std::string &warning : warnings_about_input)
          std::cerr << ("estep: warning: " + warning + "\n");
      TimeLoopResult result = run_or_resume_time_loop(*integrator,
                                                      parameters,
                                                      parameters_as_read,
                                                      initial_state,
                                                      postprocessors,
                                                      resumed_state);
      if (result.status == RunStatus::failed && rank_count() > 1)
        {
          // An output failed during the run. One of the first process's
          // own fails on it alone, while the others may still be stepping:
          // it reports the failure and ends them all. Field output, the
          // others' one output, fails on every process at once (they agree
          // on each snapshot): they leave the report and the end to the
          // first, unless it does not come.
          if (writes_output)
            {
              // Its postprocessors' finish writes only its own files (the
              // series of the snapshots written whole, for one).
              finish_postprocessors(postprocessors, result);
              report_output_failure(summary_file, record, result.message);
              end_all_ranks(exit_failed);
            }
          every_rank_arrives_within(60.);
          std::fputs(("estep: error: " + result.message + "\n").c_str(),
                     stderr);
          end_all_ranks(exit_failed);
        }
      finish_postprocessors(postprocessors, result);
      std::string summary_error;
      try
        {
          // Every rank computes the summary (its energies are collective).
          const std::string summary =
            run_summary(record, result).to_string() + "\n";
          if (writes_output)
            write_file_atomically(summary_file, summary);
        }
      catch (const std::exception &error)
        {
          if (result.status != RunStatus::failed)
            throw;
          // The disk that failed the run may not take the summary either:
          // said after the failure itself.
          summary_error = error.what();
        }

      std::cout << "estep: " << integrator->name() << " on the " << problem.name
                << ": " << to_string(result.status)
                << " at t = " << result.final_time << " after "
                << integrator->n_steps() << " steps in " << result.wall_seconds
                << " s; output in " << directory.string() << "/\n";
      for (const auto &postprocessor : postprocessors)
        if (const std::string line = postprocessor->final_report();
            !line.empty())
          std::cout << "estep: " << line << '\n';
      // The integrator's warnings that arose during the run (e.g. mostly
      // reflections), then the time loop's.
      for (const std::string &warning : integrator->warnings())
        if (std::find(warnings_at_start.begin(),
                      warnings_at_start.end(),
                      warning) == warnings_at_start.end())
          std::cerr << ("estep: warning: " + warning + "\n");
      for (const std::string &warning : result.warnings)
        std::cerr << ("estep: warning: " + warning + "\n");
      if (!result.message.empty())
        std::cerr << ("estep: " +
                      std::string(
                        result.status == RunStatus::failed ? "error: " : "") +
                      result.message + "\n");
      if (!summary_error.empty())
        std::cerr << ("estep: error: " + summary_error +
                      " The summary could not be updated either.\n");
      return exit_code(result);
    }
  } // namespace



  void
  declare_and_read_parameters(dealii::ParameterHandler       &prm,
                              const std::string              &input_file,
                              const std::vector<std::string> &overrides)
  {
    declare_parameters(prm);
    if (input_file.empty() && overrides.empty())
      return;
    if (!input_file.empty())
      read_input_file(prm, input_file, true);
    for (const std::string &text : overrides)
      try
        {
          apply_override(prm, text);
        }
      catch (const std::exception &)
        {
          // Reported by the strict reading below.
        }
    declare_parameters(prm);
    if (!input_file.empty())
      read_input_file(prm, input_file);
    for (const std::string &text : overrides)
      apply_override(prm, text);

    std::stringstream json;
    prm.print_parameters(json, dealii::ParameterHandler::JSON);
    boost::property_tree::ptree tree;
    boost::property_tree::read_json(json, tree);
    check_values(prm, tree, "");
  }



  int
  run_application(int argc, char **argv)
  {
    // deal.II's exceptions reach us as exceptions, not as aborts with a stack
    // trace.
    dealii::deal_II_exceptions::disable_abort_on_exception();
    dealii::deal_II_exceptions::suppress_stacktrace_in_exceptions();
    // A write beyond a file size limit (ulimit -f) fails (EFBIG) and is
    // reported as any output that cannot be written, instead of ending the
    // process without a word by SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    std::string error;
    try
      {
        check_lane_kernel_target();
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
        // Started by an MPI launcher as several processes: they share the
        // run, and only the first speaks and writes.
        if (const auto [launched, rank] = launched_ranks(); launched > 1)
          {
            start_mpi();
            distribute_blocks_over_mpi_ranks();
            if (rank_count() != launched)
              {
                // Another MPI's launcher: every process would be alone in
                // its MPI and run the whole problem.
                if (rank > 0) // The first process says why.
                  return exit_input_error;
                throw std::runtime_error(
                  "estep was started as " + std::to_string(launched) +
                  " MPI processes, but its MPI library sees " +
                  std::to_string(rank_count()) +
                  ": the launcher is not the one of the MPI estep was built "
                  "with (Open MPI's mpirun, package openmpi-bin), and each "
                  "process would run the whole problem into the same output "
                  "directory.");
              }
            if (this_rank() > 0)
              {
                std::cout.rdbuf(nullptr);
                std::cerr.rdbuf(nullptr);
              }
          }
        const CommandLine command = parse_command_line(argc, argv);
        if (command.help)
          {
            // With the plugins of the libraries the input names.
            load_plugin_libraries(command);
            print_help(std::cout);
            return exit_success;
          }
        if (command.version)
          {
            std::cout << "estep " << ESTEP_VERSION << " (deal.II "
                      << DEAL_II_PACKAGE_VERSION << ", cell kernels "
                      << lane_kernel_target() << ")\n";
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
        const int code = run(command);
        finish_mpi();
        return code;
      }
    catch (const dealii::ExceptionBase &exception)
      {
        error = one_line_message(exception);
      }
    catch (const std::bad_alloc &)
      {
        error = "out of memory (std::bad_alloc).";
      }
    catch (const std::exception &exception)
      {
        error = exception.what();
      }
    // An error every process met (bad input, which all check alike) is
    // reported by the first. One a process met alone leaves the others
    // waiting for it in a collective call: it reports it itself (the
    // other processes' std::cerr is silent) and ends them all.
    const std::string line = "estep: error: " + with_plugin_hint(error) + "\n";
    if (!every_rank_arrives_within(10.))
      {
        std::fputs(line.c_str(), stderr);
        end_all_ranks(exit_input_error);
      }
    std::cerr << line;
    finish_mpi();
    return exit_input_error;
  }
} // namespace estep
