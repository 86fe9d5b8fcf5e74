#include <estep/composite/system_decorator.h>

#include <stdexcept>

namespace estep
{
  SystemDecorator::SystemDecorator(std::shared_ptr<const MechanicalSystem> base)
    : base_system(std::move(base))
  {
    if (!base_system)
      throw std::invalid_argument("SystemDecorator: no base system.");
  }



  const MechanicalSystem &
  SystemDecorator::base() const
  {
    return *base_system;
  }



  std::string
  SystemDecorator::name() const
  {
    return base_system->name();
  }



  unsigned int
  SystemDecorator::spatial_dimension() const
  {
    return base_system->spatial_dimension();
  }



  unsigned int
  SystemDecorator::n_dofs() const
  {
    return base_system->n_dofs();
  }



  const Vector &
  SystemDecorator::inverse_mass() const
  {
    return base_system->inverse_mass();
  }



  double
  SystemDecorator::energy(const Vector &q) const
  {
    return base_system->energy(q);
  }



  void
  SystemDecorator::gradient(const Vector &q, Vector &g) const
  {
    base_system->gradient(q, g);
  }



  std::unique_ptr<FreeFlight>
  SystemDecorator::free_flight(const Vector &q, const Vector &v) const
  {
    return base_system->free_flight(q, v);
  }



  std::optional<ConstraintEvent>
  SystemDecorator::first_constraint_event(const Vector &q,
                                          const Vector &v,
                                          const double  s_max) const
  {
    return base_system->first_constraint_event(q, v, s_max);
  }



  std::vector<SparseNormal>
  SystemDecorator::touching_constraints(const Vector &q) const
  {
    return base_system->touching_constraints(q);
  }



  bool
  SystemDecorator::has_constraints() const
  {
    return base_system->has_constraints();
  }



  bool
  SystemDecorator::has_hessian() const
  {
    return base_system->has_hessian();
  }



  const dealii::SparsityPattern &
  SystemDecorator::hessian_sparsity() const
  {
    return base_system->hessian_sparsity();
  }



  void
  SystemDecorator::hessian(const Vector                 &q,
                           dealii::SparseMatrix<double> &H) const
  {
    base_system->hessian(q, H);
  }



  std::vector<std::string>
  SystemDecorator::observable_names() const
  {
    return base_system->observable_names();
  }



  std::vector<double>
  SystemDecorator::observables(const Vector &q, const Vector &v) const
  {
    return base_system->observables(q, v);
  }



  std::string
  SystemDecorator::penetration(const Vector &q) const
  {
    return base_system->penetration(q);
  }



  double
  SystemDecorator::penalty_energy_scale() const
  {
    return base_system->penalty_energy_scale();
  }



  const std::vector<BlockRange> *
  SystemDecorator::kept_coordinates() const
  {
    return shares_base_state ? base_system->kept_coordinates() : nullptr;
  }



  void
  SystemDecorator::kept_gradient(const Vector &q, Vector &g) const
  {
    if (shares_base_state)
      base_system->kept_gradient(q, g);
    else
      gradient(q, g);
  }



  void
  SystemDecorator::complete_state(Vector &x) const
  {
    if (shares_base_state)
      base_system->complete_state(x);
  }



  void
  SystemDecorator::base_kept_gradient(const Vector &q, Vector &g) const
  {
    if (shares_base_state)
      base_system->kept_gradient(q, g);
    else
      base_system->gradient(q, g);
  }
} // namespace estep
