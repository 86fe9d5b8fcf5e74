#include <deal.II/base/parameter_handler.h>

#include <estep/base/json_writer.h>
#include <estep/io/step_histogram.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace estep
{
  StepHistogram::StepHistogram(const std::string &filename,
                               const double       end_time)
    : filename(filename)
    , end_time(end_time)
    , bins((max_exponent - min_exponent) * bins_per_decade, 0)
  {}



  void
  StepHistogram::after_step(const TimeIntegrator &integrator)
  {
    if (integrator.time() == end_time)
      return;
    const double dt = integrator.time() - integrator.previous_time();
    if (!(dt > 0.))
      return;
    const long bin = std::lround(
      std::floor((std::log10(dt) - min_exponent) * bins_per_decade));
    if (bin >= 0 && bin < static_cast<long>(bins.size()))
      ++bins[bin];
  }

  void
  StepHistogram::save_state(StateWriter &out) const
  {
    for (const std::uint64_t count : bins)
      out.put(count);
  }



  void
  StepHistogram::resume(StateReader &in)
  {
    for (std::uint64_t &count : bins)
      count = in.get<std::uint64_t>();
  }



  void
  StepHistogram::finish(const TimeLoopResult &)
  {
    std::size_t first = 0, last = bins.size();
    while (first < last && bins[first] == 0)
      ++first;
    while (last > first && bins[last - 1] == 0)
      --last;
    std::ostringstream out;
    out << "lower,upper,count\n";
    out.precision(6);
    for (std::size_t i = first; i < last; ++i)
      out << std::pow(10., min_exponent + double(i) / bins_per_decade) << ','
          << std::pow(10., min_exponent + double(i + 1) / bins_per_decade)
          << ',' << bins[i] << '\n';
    write_file_atomically(filename, out.str());
  }



  namespace
  {
    std::unique_ptr<Postprocessor>
    create_step_histogram(dealii::ParameterHandler &,
                          const PostprocessorContext &run)
    {
      return std::make_unique<StepHistogram>(
        (std::filesystem::path(run.output_directory) / "step_histogram.csv")
          .string(),
        run.end_time);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_POSTPROCESSOR(
  "step histogram",
  "step_histogram.csv: the number of time steps in logarithmic bins of their "
  "length (ten per decade), written at the end.",
  nullptr,
  estep::create_step_histogram)
