// What the parallel benchmarks share: energy-stepping (h = 1e-5) of the
// spinning cube of the reference text rotating about its centre (or of a
// ball of its material), timed, and the comparison of two final states to
// the last bit.
#ifndef estep_benchmarks_centred_cube_run_h
#define estep_benchmarks_centred_cube_run_h

#include <deal.II/grid/tria.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/ball_mesh.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/materials/neo_hookean.h>
#include <estep/time_integration/energy_stepping.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace benchmark_cube
{
  struct Run
  {
    double        seconds;
    unsigned int  steps;
    double        time;
    estep::Vector q, v;
  };

  /** Energy-stepping of @p body from the rotation about the z axis through
   * @p centre (the cube's centre by default) at unit angular velocity to
   * @p end_time or @p max_steps steps, whichever comes first. */
  inline Run
  run(const estep::ElasticBody    &body,
      const double                 end_time,
      const unsigned int           max_steps,
      const std::array<double, 3> &centre = {{0.5, 0.5, 0.5}})
  {
    const estep::Vector q = body.reference_configuration();
    const estep::Vector v =
      body.rigid_velocity(q, {{0., 0., 0.}}, {{0., 0., 1.}}, centre);
    estep::EnergyStepping stepping(body, 1e-5);
    stepping.initialize(0., q, v);
    const auto start = std::chrono::steady_clock::now();
    while (stepping.time() < end_time && stepping.n_steps() < max_steps)
      stepping.step(end_time);
    // (On several MPI ranks each kept only its part of the state.)
    stepping.complete_state();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    return {seconds,
            static_cast<unsigned int>(stepping.n_steps()),
            stepping.time(),
            stepping.position(),
            stepping.velocity()};
  }

  /** The neo-Hookean body of the reference text's cube on @p tria. */
  inline estep::ElasticBody
  body_on(const dealii::Triangulation<3> &tria, const std::string &name)
  {
    return estep::ElasticBody(
      tria, std::make_shared<estep::NeoHookean>(0.0100, 0.0066), 0.100, name);
  }

  /** A unit ball of gmsh (mesh size 0.05: 152,424 cells), its cells in
   * gmsh's order in @p trias[0] and along the Hilbert curve of the mesh
   * factory in @p trias[1] (both empty before). */
  inline void
  make_ball_in_two_orders(std::array<dealii::Triangulation<3>, 2> &trias)
  {
    estep::make_ball_mesh(trias[0], 0.05);
    trias[1].copy_triangulation(trias[0]);
    estep::order_cells_along_hilbert_curve(trias[1]);
  }

  /** Whether two runs ended in the same state, to the last bit. */
  inline bool
  same_end(const Run &a, const Run &b)
  {
    const auto same = [](const estep::Vector &x, const estep::Vector &y) {
      return x.size() == y.size() &&
             std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
    };
    return a.steps == b.steps && same(a.q, b.q) && same(a.v, b.v);
  }

  /**
   * The last table of the parallel benchmarks: the ball of
   * make_ball_in_two_orders() spinning about its centre for 40 steps, in each
   * order of its cells run by @p one_and_many(body, centre, steps), which
   * returns its run on one thread or process and on several ("N" or "P",
   * @p many). If @p print, a row per order: the times per step, the speedup,
   * whether the two runs ended in the same bits, and the cells each of 2 MPI
   * ranks holds (chunks_held_by_ranks()) relative to its own; then the
   * ratios of the two orders' times, on one (@p one: "1 thread") and on
   * several.
   */
  template <typename OneAndMany>
  void
  compare_cell_orders(const OneAndMany &one_and_many,
                      const char       *one,
                      const char       *many,
                      const bool        print)
  {
    if (print)
      {
        std::printf("\nthe same, 40 steps of a ball of gmsh (mesh size 0.05) "
                    "spinning about its centre, in two orders of its cells\n");
        std::printf("%-14s %9s %13s %10s: s/step %8s %9s %17s\n",
                    "cell order",
                    "cells",
                    "1: s/step",
                    many,
                    "speedup",
                    "same bits",
                    "held of 2 ranks");
      }
    std::array<dealii::Triangulation<3>, 2> balls;
    make_ball_in_two_orders(balls);
    std::array<double, 2> seconds_one{}, seconds_many{};
    for (const unsigned int k : {0u, 1u})
      {
        const estep::ElasticBody body = body_on(balls[k], "ball");
        const auto [single, several]  = one_and_many(body, {{0., 0., 0.}}, 40);
        seconds_one[k]                = single.seconds;
        seconds_many[k]               = several.seconds;
        const estep::P1CellData &data = body.cell_data();
        const auto               held = estep::chunks_held_by_ranks(data, 2);
        std::array<double, 2>    ratio{};
        for (const unsigned int r : {0u, 1u})
          {
            const estep::BlockRange own = estep::rank_cells(data.n_cells, r, 2);
            ratio[r] = double(data.n_cells_in(held[r])) / (own.end - own.begin);
          }
        if (print)
          std::printf("%-14s %9u %13.3e %18.3e %8.2f %9s %8.2f %8.2f\n",
                      k == 0 ? "gmsh's" : "Hilbert curve",
                      body.n_cells(),
                      single.seconds / single.steps,
                      several.seconds / several.steps,
                      single.seconds / several.seconds,
                      same_end(single, several) ? "yes" : "NO",
                      ratio[0],
                      ratio[1]);
      }
    if (print)
      std::printf("time in gmsh's order / along the curve: %.2f on %s, "
                  "%.2f on %s\n",
                  seconds_one[0] / seconds_one[1],
                  one,
                  seconds_many[0] / seconds_many[1],
                  many);
  }
} // namespace benchmark_cube

#endif
