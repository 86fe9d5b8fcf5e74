// A user's own postprocessor as an estep plugin: the largest speed of any
// degree of freedom at the end of any step, and when it happened, added to
// summary.json as "max speed". Add `max speed` to `Postprocessors/List`.
#include <deal.II/base/parameter_handler.h>

#include <estep/io/postprocessor.h>

#include <cmath>

namespace
{
  class MaxSpeed : public estep::Postprocessor
  {
  public:
    void
    after_step(const estep::TimeIntegrator &integrator) override
    {
      const double speed = integrator.velocity().linfty_norm();
      if (speed > largest)
        {
          largest = speed;
          time    = integrator.time();
        }
    }

    void
    add_to_summary(estep::JsonObject &summary) const override
    {
      summary.add("max speed",
                  estep::JsonObject().add("value", largest).add("time", time));
    }

    /** For checkpoints: what it has found so far. */
    void
    save_state(estep::StateWriter &out) const override
    {
      out.put(largest);
      out.put(time);
    }

    void
    resume(estep::StateReader &in) override
    {
      largest = in.get<double>();
      time    = in.get<double>();
    }

  private:
    double largest = 0., time = 0.;
  };

  std::unique_ptr<estep::Postprocessor>
  create_max_speed(dealii::ParameterHandler &,
                   const estep::PostprocessorContext &)
  {
    return std::make_unique<MaxSpeed>();
  }
} // namespace

ESTEP_REGISTER_POSTPROCESSOR("max speed",
                             "the largest velocity component at a step end "
                             "and its time, in summary.json: the example "
                             "plugin.",
                             nullptr,
                             create_max_speed)
