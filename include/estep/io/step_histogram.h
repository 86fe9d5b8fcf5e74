#ifndef estep_io_step_histogram_h
#define estep_io_step_histogram_h

#include <estep/io/postprocessor.h>

#include <cstdint>
#include <string>
#include <vector>

namespace estep
{
  /**
   * The histogram of the time steps a run takes, in logarithmic bins (ten per
   * decade from 1e-15 to 1e5). A step cut short by the end time is not counted.
   * step_histogram.csv has the columns lower, upper, count.
   */
  class StepHistogram : public Postprocessor
  {
  public:
    /** The histogram of a run ending at @p end_time (the step ending there is
     * the truncated last one and is left out), written to @p filename. */
    StepHistogram(const std::string &filename, const double end_time);

    void
    after_step(const TimeIntegrator &integrator) override;

    /** The counts. */
    void
    save_state(StateWriter &out) const override;

    void
    resume(StateReader &in) override;

    /** Write the non-empty range of bins as CSV (atomically). */
    void
    finish(const TimeLoopResult &result) override;

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
    std::string                filename;
    double                     end_time;
    std::vector<std::uint64_t> bins;
  };
} // namespace estep

#endif
