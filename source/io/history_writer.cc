#include <deal.II/base/parameter_handler.h>

#include <estep/io/history_writer.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <stdexcept>

namespace estep
{
  HistoryWriter::HistoryWriter(const std::string    &filename,
                               const TimeIntegrator &integrator)
    : integrator(integrator)
    , filename(filename)
    , start_time(integrator.time())
    , smallest_step_since_row(std::numeric_limits<double>::infinity())
    , largest_step_since_row(0.)
  {}



  void
  HistoryWriter::start()
  {
    out.open(filename);
    if (!out)
      throw std::runtime_error("Cannot open the history file <" + filename +
                               "> for writing.");
    out << "time,kinetic_energy,potential_energy,terraced_potential_energy,"
           "total_energy,terraced_total_energy,"
           "linear_momentum_x,linear_momentum_y,linear_momentum_z,"
           "angular_momentum_x,angular_momentum_y,angular_momentum_z,"
           "steps,mean_step,min_step,max_step";
    for (const std::string &name :
         integrator.mechanical_system().observable_names())
      out << ',' << name;
    out << '\n' << std::setprecision(16);
    out.flush();
    if (!out)
      throw std::runtime_error("Cannot write the history file <" + filename +
                               ">.");
    bytes_written = out.tellp();
  }



  void
  HistoryWriter::save_state(StateWriter &state) const
  {
    state.put(bytes_written);
    state.put(smallest_step_since_row);
    state.put(largest_step_since_row);
  }



  void
  HistoryWriter::resume(StateReader &state)
  {
    bytes_written           = state.get<std::uint64_t>();
    smallest_step_since_row = state.get<double>();
    largest_step_since_row  = state.get<double>();
    std::error_code error;
    if (std::filesystem::file_size(filename, error) < bytes_written || error)
      throw std::runtime_error("Cannot resume the history file <" + filename +
                               ">: it is missing or shorter than at the "
                               "checkpoint.");
    std::filesystem::resize_file(filename, bytes_written);
    out.open(filename, std::ios::app | std::ios::ate);
    out << std::setprecision(16);
    if (!out)
      throw std::runtime_error("Cannot open the history file <" + filename +
                               "> for appending.");
  }



  void
  HistoryWriter::observe(const Snapshot &s)
  {
    const MechanicalSystem &system  = integrator.mechanical_system();
    const Momenta           momenta = compute_momenta(system, s.q, s.v);
    const std::uint64_t     steps   = integrator.n_steps();
    out << s.t << ',' << s.kinetic_energy << ',' << s.potential_energy << ','
        << s.terraced_potential_energy << ','
        << s.kinetic_energy + s.potential_energy << ','
        << s.kinetic_energy + s.terraced_potential_energy;
    for (const double p : momenta.linear)
      out << ',' << p;
    for (const double l : momenta.angular)
      out << ',' << l;
    out << ',' << steps << ',';
    if (steps > 0)
      out << (integrator.time() - start_time) / static_cast<double>(steps);
    else
      out << 0;
    if (smallest_step_since_row > largest_step_since_row)
      {
        const double step = integrator.time() - integrator.previous_time();
        out << ',' << step << ',' << step;
      }
    else
      out << ',' << smallest_step_since_row << ',' << largest_step_since_row;
    smallest_step_since_row = std::numeric_limits<double>::infinity();
    largest_step_since_row  = 0.;
    for (const double x : system.observables(s.q, s.v))
      out << ',' << x;
    out << '\n';
    out.flush();
    if (!out)
      {
        // The part of the row that reached the file goes: the file ends
        // with its last whole row, as a reader of it expects.
        out.close();
        std::error_code ignored;
        std::filesystem::resize_file(filename, bytes_written, ignored);
        throw OutputFailed("Writing a row of the history file <" + filename +
                           "> failed (is the disk full?).");
      }
    bytes_written = out.tellp();
  }



  void
  HistoryWriter::after_step(const TimeIntegrator &stepper)
  {
    const double step       = stepper.time() - stepper.previous_time();
    smallest_step_since_row = std::min(smallest_step_since_row, step);
    largest_step_since_row  = std::max(largest_step_since_row, step);
  }



  namespace
  {
    std::unique_ptr<Postprocessor>
    create_history(dealii::ParameterHandler &, const PostprocessorContext &run)
    {
      return std::make_unique<HistoryWriter>(
        (std::filesystem::path(run.output_directory) / "history.csv").string(),
        run.integrator);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_POSTPROCESSOR(
  "history",
  "history.csv: a row every Output/History interval with the time, the "
  "energies, the momenta, the step statistics and the system's observables "
  "(e.g. a tracked point).",
  nullptr,
  estep::create_history)
