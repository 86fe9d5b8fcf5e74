#ifndef estep_io_step_histogram_h
#define estep_io_step_histogram_h

#include <estep/time_integration/time_loop.h>

#include <cstdint>
#include <string>
#include <vector>

namespace estep
{
  /**
   * The histogram of the time steps a run takes, in logarithmic bins (ten per
   * decade from 1e-15 to 1e5). A step cut short by the end time is not counted.
   * write() produces step_histogram.csv with the columns lower, upper, count.
   */
  class StepHistogram : public RunObserver
  {
  public:
    StepHistogram();

    /** @p end_time: the step ending there is the truncated last one and is left
     * out. */
    void
    set_end_time(const double end_time);

    void
    after_step(const TimeIntegrator &integrator) override;

    /** Write the non-empty range of bins as CSV (atomically). */
    void
    write(const std::string &filename) const;

    /** The counts per bin, and the lower edge of bin i: 10^(min_exponent + i /
     * 10). */
    const std::vector<std::uint64_t> &
    counts() const
    {
      return bins;
    }

    static constexpr int bins_per_decade = 10;
    static constexpr int min_exponent    = -15;
    static constexpr int max_exponent    = 5;

  private:
    std::vector<std::uint64_t> bins;
    double                     end_time = 0.;
    bool                       has_end  = false;
  };
} // namespace estep

#endif
