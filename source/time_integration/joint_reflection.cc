#include <estep/time_integration/joint_reflection.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace estep
{
  namespace
  {
    constexpr double unit = std::numeric_limits<double>::epsilon() / 2.;

    /**
     * Solves the symmetric positive definite system A x = b (A n x n, row
     * by row) by Cholesky's factorisation; false if a pivot is not clearly
     * positive (a normal dependent on the others up to round-off).
     */
    bool
    solve_positive_definite(std::vector<double>  A,
                            std::vector<double> &x,
                            const std::size_t    n)
    {
      for (std::size_t j = 0; j < n; ++j)
        {
          double pivot = A[j * n + j];
          for (std::size_t k = 0; k < j; ++k)
            pivot -= A[j * n + k] * A[j * n + k];
          if (!(pivot > 1e-10 * A[j * n + j]))
            return false;
          A[j * n + j] = std::sqrt(pivot);
          for (std::size_t i = j + 1; i < n; ++i)
            {
              double a = A[i * n + j];
              for (std::size_t k = 0; k < j; ++k)
                a -= A[i * n + k] * A[j * n + k];
              A[i * n + j] = a / A[j * n + j];
            }
        }
      for (std::size_t i = 0; i < n; ++i)
        {
          for (std::size_t k = 0; k < i; ++k)
            x[i] -= A[i * n + k] * x[k];
          x[i] /= A[i * n + i];
        }
      for (std::size_t i = n; i-- > 0;)
        {
          for (std::size_t k = i + 1; k < n; ++k)
            x[i] -= A[k * n + i] * x[k];
          x[i] /= A[i * n + i];
        }
      return true;
    }

    /** n . w. */
    double
    rate_of(const SparseNormal &normal, const Vector &w)
    {
      double r = 0.;
      for (const auto &[i, value] : normal)
        r += value * w[i];
      return r;
    }

    /** N x, or M^-1 N x with @p inverse_mass. */
    Vector
    combination(const std::vector<SparseNormal> &normals,
                const std::vector<double>       &x,
                const unsigned int               size,
                const Vector                    *inverse_mass = nullptr)
    {
      Vector n(size);
      for (std::size_t k = 0; k < normals.size(); ++k)
        if (x[k] != 0.)
          for (const auto &[i, value] : normals[k])
            n[i] += x[k] * value * (inverse_mass ? (*inverse_mass)[i] : 1.);
      return n;
    }

    /** The rates n_k . v and their round-off. */
    std::pair<std::vector<double>, std::vector<double>>
    rates_and_slack(const std::vector<SparseNormal> &normals, const Vector &v)
    {
      std::vector<double> rate(normals.size(), 0.), slack(normals.size(), 0.);
      for (std::size_t k = 0; k < normals.size(); ++k)
        for (const auto &[i, value] : normals[k])
          {
            rate[k] += value * v[i];
            slack[k] += 256. * unit * std::abs(value * v[i]);
          }
      return {rate, slack};
    }

    /**
     * Lawson and Hanson's active set for the multipliers x >= 0 with
     * w = q + G x >= 0 and x . w = 0 (G = N^T M^-1 N); a pair enters while
     * its w_k < -slack_k, the round-off of q_k.
     */
    std::vector<double>
    complementary_multipliers(const std::vector<SparseNormal> &normals,
                              const std::vector<double>       &q,
                              const std::vector<double>       &slack,
                              const Vector                    &inverse_mass)
    {
      const std::size_t K = normals.size();
      // The set's multipliers x > 0, and u = M^-1 N x, the change of the
      // velocity they make.
      std::vector<double>      x(K, 0.);
      std::vector<bool>        in_set(K, false), left_out(K, false);
      std::vector<std::size_t> set;
      Vector                   u(inverse_mass.size()), column(u.size());
      // The multipliers z that make w zero on the set: G_set z = -q_set;
      // false if G_set is singular up to round-off.
      const auto solve_on_set = [&](std::vector<double> &z) {
        const std::size_t   n = set.size();
        std::vector<double> G(n * n);
        for (std::size_t a = 0; a < n; ++a)
          {
            for (const auto &[i, value] : normals[set[a]])
              column[i] = inverse_mass[i] * value;
            for (std::size_t b = 0; b <= a; ++b)
              G[a * n + b] = G[b * n + a] = rate_of(normals[set[b]], column);
            for (const auto &[i, value] : normals[set[a]])
              column[i] = 0.;
          }
        z.resize(n);
        for (std::size_t a = 0; a < n; ++a)
          z[a] = -q[set[a]];
        return solve_positive_definite(G, z, n);
      };

      for (std::size_t iteration = 0; iteration < 3 * K + 3; ++iteration)
        {
          // The pair whose w is lowest enters.
          std::size_t entering = K;
          double      lowest   = 0.;
          for (std::size_t k = 0; k < K; ++k)
            if (!in_set[k] && !left_out[k])
              {
                const double w = q[k] + rate_of(normals[k], u);
                if (w < -slack[k] && w < lowest)
                  {
                    lowest   = w;
                    entering = k;
                  }
              }
          if (entering == K)
            break;
          set.push_back(entering);
          in_set[entering] = true;
          std::vector<double> z;
          for (bool first = true;; first = false)
            {
              const bool solved = solve_on_set(z);
              if (first && (!solved || !(z.back() > 0.)))
                {
                  // Dependent on the set up to round-off: left out.
                  set.pop_back();
                  in_set[entering]   = false;
                  left_out[entering] = true;
                  break;
                }
              if (solved && std::all_of(z.begin(), z.end(), [](const double y) {
                    return y > 0.;
                  }))
                {
                  for (std::size_t a = 0; a < set.size(); ++a)
                    x[set[a]] = z[a];
                  break;
                }
              // Towards z until a multiplier reaches zero: that pair leaves
              // (with every other at zero).
              double      step    = 1.;
              std::size_t leaving = K;
              for (std::size_t a = 0; a < set.size(); ++a)
                if (!solved || z[a] <= 0.)
                  {
                    const double to_zero =
                      solved ? x[set[a]] / (x[set[a]] - z[a]) : 0.;
                    if (leaving == K || to_zero < step)
                      {
                        step    = to_zero;
                        leaving = set[a];
                      }
                  }
              std::vector<std::size_t> kept;
              for (std::size_t a = 0; a < set.size(); ++a)
                {
                  const std::size_t k = set[a];
                  if (solved)
                    x[k] += step * (z[a] - x[k]);
                  if (k != leaving && x[k] > 0.)
                    kept.push_back(k);
                  else
                    {
                      x[k]      = 0.;
                      in_set[k] = false;
                    }
                }
              set = kept;
              if (set.empty())
                break;
            }
          u = combination(normals, x, u.size(), &inverse_mass);
        }
      return x;
    }
  } // namespace



  Vector
  parting_projection_normal(const std::vector<SparseNormal> &normals,
                            const Vector                    &v,
                            const Vector                    &inverse_mass)
  {
    const auto [rate, slack] = rates_and_slack(normals, v);
    return combination(
      normals,
      complementary_multipliers(normals, rate, slack, inverse_mass),
      v.size());
  }



  Vector
  joint_reflection_normal(const std::vector<SparseNormal> &normals,
                          const Vector                    &v,
                          const Vector                    &inverse_mass)
  {
    const std::size_t K      = normals.size();
    const auto [rate, slack] = rates_and_slack(normals, v);
    const std::vector<double> lambda =
      complementary_multipliers(normals, rate, slack, inverse_mass);
    const Vector mirror = combination(normals, lambda, v.size());
    if (mirror.linfty_norm() == 0.)
      return mirror;

    // w = N^T v_p, and twice the kinetic energy the projection takes,
    // lambda . G lambda.
    const Vector u = combination(normals, lambda, v.size(), &inverse_mass);
    std::vector<double> w(K);
    double              taken = 0.;
    for (std::size_t k = 0; k < K; ++k)
      {
        const double change = rate_of(normals[k], u);
        w[k]                = rate[k] + change;
        taken += lambda[k] * change;
      }

    // The multipliers that part every pair that approached at least at the
    // speed it approached at, and hold every other.
    std::vector<double> demand(K, 0.), demand_slack(K, 0.);
    for (std::size_t k = 0; k < K; ++k)
      if (rate[k] < -slack[k])
        {
          demand[k]       = rate[k];
          demand_slack[k] = slack[k];
        }
    const std::vector<double> mu =
      complementary_multipliers(normals, demand, demand_slack, inverse_mass);
    const Vector        d = combination(normals, mu, v.size(), &inverse_mass);
    std::vector<double> parting(K);
    double              a = 0., b = 0.;
    for (std::size_t k = 0; k < K; ++k)
      {
        parting[k] = rate_of(normals[k], d);
        a += mu[k] * parting[k];
        b += mu[k] * w[k];
      }
    if (!(a > 0. && taken > 0.))
      return mirror;
    // |v_p + tau d|^2 = |v_p|^2 + taken, in its cancellation-free form.
    const double tau = taken / (b + std::sqrt(b * b + a * taken));
    // Round-off, or a jam, may leave pairs approaching: the mirror image
    // (rates 2 w - n . v) where it leaves none approaching faster, or where
    // a pair that approached does not part.
    double after = 0., after_mirror = 0.;
    for (std::size_t k = 0; k < K; ++k)
      {
        const double rate_after = w[k] + tau * parting[k];
        if (rate[k] < -slack[k] && !(rate_after > 0.))
          return mirror;
        after        = std::min(after, rate_after);
        after_mirror = std::min(after_mirror, 2. * w[k] - rate[k]);
      }
    if (after < after_mirror)
      return mirror;
    std::vector<double> x(K);
    for (std::size_t k = 0; k < K; ++k)
      x[k] = lambda[k] + tau * mu[k];
    return combination(normals, x, v.size());
  }
} // namespace estep
