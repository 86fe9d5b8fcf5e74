#include <estep/io/json_writer.h>
#include <estep/io/step_histogram.h>

#include <cmath>
#include <sstream>

namespace estep
{
  StepHistogram::StepHistogram()
    : bins((max_exponent - min_exponent) * bins_per_decade, 0)
  {}

  void
  StepHistogram::set_end_time(const double t_end)
  {
    end_time = t_end;
    has_end  = true;
  }

  void
  StepHistogram::after_step(const TimeIntegrator &integrator)
  {
    if (has_end && integrator.time() == end_time)
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
  StepHistogram::write(const std::string &filename) const
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
} // namespace estep
