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
  } // namespace



  Vector
  joint_reflection_normal(const std::vector<SparseNormal> &normals,
                          const Vector                    &v,
                          const Vector                    &inverse_mass)
  {
    const std::size_t K = normals.size();
    Vector            joint(v.size());
    // The rates n_k . v, and their round-off.
    std::vector<double> rate(K, 0.), slack(K, 0.);
    for (std::size_t k = 0; k < K; ++k)
      for (const auto &[i, value] : normals[k])
        {
          rate[k] += value * v[i];
          slack[k] += std::abs(value * v[i]);
        }
    for (double &s : slack)
      s *= 256. * unit;

    // Lawson and Hanson's active set with its multipliers lambda > 0, and
    // u = M^-1 N lambda, the change of the velocity they make.
    std::vector<double>      lambda(K, 0.);
    std::vector<bool>        in_set(K, false), left_out(K, false);
    std::vector<std::size_t> set;
    Vector                   u(v.size()), column(v.size());
    const auto rate_of = [&](const std::size_t k, const Vector &w) {
      double r = 0.;
      for (const auto &[i, value] : normals[k])
        r += value * w[i];
      return r;
    };
    // The multipliers z that make the rates of the set's pairs zero:
    // G_set z = -rates; false if G_set is singular up to round-off.
    const auto solve_on_set = [&](std::vector<double> &z) {
      const std::size_t   n = set.size();
      std::vector<double> G(n * n);
      for (std::size_t a = 0; a < n; ++a)
        {
          for (const auto &[i, value] : normals[set[a]])
            column[i] = inverse_mass[i] * value;
          for (std::size_t b = 0; b <= a; ++b)
            G[a * n + b] = G[b * n + a] = rate_of(set[b], column);
          for (const auto &[i, value] : normals[set[a]])
            column[i] = 0.;
        }
      z.resize(n);
      for (std::size_t a = 0; a < n; ++a)
        z[a] = -rate[set[a]];
      return solve_positive_definite(G, z, n);
    };

    for (std::size_t iteration = 0; iteration < 3 * K + 3; ++iteration)
      {
        // The pair that approaches fastest after the change so far enters.
        std::size_t entering = K;
        double      fastest  = 0.;
        for (std::size_t k = 0; k < K; ++k)
          if (!in_set[k] && !left_out[k])
            {
              const double w = rate[k] + rate_of(k, u);
              if (w < -slack[k] && w < fastest)
                {
                  fastest  = w;
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
            if (solved && std::all_of(z.begin(), z.end(), [](const double x) {
                  return x > 0.;
                }))
              {
                for (std::size_t a = 0; a < set.size(); ++a)
                  lambda[set[a]] = z[a];
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
                    solved ? lambda[set[a]] / (lambda[set[a]] - z[a]) : 0.;
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
                  lambda[k] += step * (z[a] - lambda[k]);
                if (k != leaving && lambda[k] > 0.)
                  kept.push_back(k);
                else
                  {
                    lambda[k] = 0.;
                    in_set[k] = false;
                  }
              }
            set = kept;
            if (set.empty())
              break;
          }
        u = 0.;
        for (const std::size_t k : set)
          for (const auto &[i, value] : normals[k])
            u[i] += lambda[k] * inverse_mass[i] * value;
      }

    for (const std::size_t k : set)
      for (const auto &[i, value] : normals[k])
        joint[i] += lambda[k] * value;
    return joint;
  }
} // namespace estep
