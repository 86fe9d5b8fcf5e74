#include <estep/systems/mechanical_system.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  bool
  MechanicalSystem::has_constraints() const
  {
    return false;
  }



  std::optional<ConstraintEvent>
  MechanicalSystem::first_constraint_event(const Vector &,
                                           const Vector &,
                                           const double) const
  {
    return std::nullopt;
  }



  std::vector<SparseNormal>
  MechanicalSystem::touching_constraints(const Vector &) const
  {
    return {};
  }

  bool
  MechanicalSystem::has_hessian() const
  {
    return false;
  }

  const dealii::SparsityPattern &
  MechanicalSystem::hessian_sparsity() const
  {
    throw std::logic_error("The system <" + name() +
                           "> provides no Hessian (tangent stiffness).");
  }

  void
  MechanicalSystem::hessian(const Vector &,
                            dealii::SparseMatrix<double> &) const
  {
    throw std::logic_error("The system <" + name() +
                           "> provides no Hessian (tangent stiffness).");
  }

  const std::vector<BlockRange> *
  MechanicalSystem::kept_coordinates() const
  {
    return nullptr;
  }

  void
  MechanicalSystem::kept_gradient(const Vector &q, Vector &g) const
  {
    gradient(q, g);
  }

  void
  MechanicalSystem::complete_state(Vector &) const
  {}

  std::vector<std::string>
  MechanicalSystem::observable_names() const
  {
    return {};
  }

  std::vector<double>
  MechanicalSystem::observables(const Vector &, const Vector &) const
  {
    return {};
  }

  std::string
  MechanicalSystem::penetration(const Vector &) const
  {
    return "";
  }

  double
  MechanicalSystem::penalty_energy_scale() const
  {
    return std::numeric_limits<double>::infinity();
  }

  Momenta
  compute_momenta(const MechanicalSystem &system,
                  const Vector           &q,
                  const Vector           &v)
  {
    const unsigned int dim      = system.spatial_dimension();
    const Vector      &inv_mass = system.inverse_mass();
    Momenta            m;
    for (unsigned int i = 0; i + dim <= q.size(); i += dim)
      {
        double x[3] = {0., 0., 0.}, p[3] = {0., 0., 0.};
        for (unsigned int c = 0; c < dim; ++c)
          {
            x[c] = q[i + c];
            p[c] = v[i + c] / inv_mass[i + c];
            m.linear[c] += p[c];
          }
        m.angular[0] += x[1] * p[2] - x[2] * p[1];
        m.angular[1] += x[2] * p[0] - x[0] * p[2];
        m.angular[2] += x[0] * p[1] - x[1] * p[0];
      }
    return m;
  }

  double
  kinetic_energy(const MechanicalSystem &system, const Vector &v)
  {
    const Vector &inv_mass = system.inverse_mass();
    double        t        = 0.;
    for (unsigned int i = 0; i < v.size(); ++i)
      t += v[i] * v[i] / inv_mass[i];
    return 0.5 * t;
  }



  bool
  all_finite(const MechanicalSystem                     &system,
             const std::initializer_list<const Vector *> vectors)
  {
    const unsigned int n = system.n_dofs();
    return sum_over_coordinate_blocks<unsigned int>(
             system, [&](const unsigned int b) {
               const BlockRange dofs = block_range(b, n);
               return unsigned(std::all_of(
                 vectors.begin(), vectors.end(), [&](const Vector *x) {
                   return std::all_of(x->begin() + dofs.begin,
                                      x->begin() + dofs.end,
                                      [](const double value) {
                                        return std::isfinite(value);
                                      });
                 }));
             }) == n_blocks(n);
  }
} // namespace estep
