#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/json_writer.h>
#include <estep/base/mpi_session.h>
#include <estep/fem/elastic_body.h>
#include <estep/io/field_output.h>
#include <estep/io/vtu_file.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace estep
{
  struct FieldOutput::Implementation
  {
    /** This process's piece of a body: the cells of its blocks (all on one
     * process) and, on several, the points they use. */
    struct Piece
    {
      BlockRange                cells;
      std::vector<unsigned int> points;
    };

    Implementation(const ElasticBodies &bodies,
                   const std::string   &directory,
                   const Format         format,
                   const double         start_time,
                   const double         interval)
      : bodies(bodies)
      , directory(directory)
      , format(format)
      , interval(interval)
      , next_time(start_time)
      , mapping(dealii::FE_SimplexP<3>(1))
      , rank(this_rank())
      , ranks(rank_count())
    {
      if (format == Format::hdf5)
        {
          // The first process writes the whole body: every process sends it
          // its cells.
          const P1CellData &every = bodies.body(0).every_cell_data();
          if (rank == 0)
            make_dof_handler(every);
          return;
        }
      for (unsigned int b = 0; b < bodies.n_bodies(); ++b)
        {
          const P1CellData &cells = bodies.body(b).cell_data();
          if (ranks == 1)
            {
              std::vector<unsigned int> tetrahedra(4 *
                                                   std::size_t(cells.n_cells));
              for (unsigned int e = 0; e < cells.n_cells; ++e)
                for (unsigned int a = 0; a < 4; ++a)
                  tetrahedra[4 * e + a] = cells.point[a][cells.at(e)];
              vtu.push_back(std::make_unique<VtuFile>(cells.reference_position,
                                                      tetrahedra));
              pieces.push_back({{0, cells.n_cells}, {}});
              continue;
            }
          // This process's piece: the cells of its blocks and their points.
          Piece piece;
          piece.cells                      = rank_cells(cells.n_cells, rank);
          constexpr unsigned int    unused = -1;
          std::vector<unsigned int> local(cells.n_points, unused);
          for (unsigned int e = piece.cells.begin; e < piece.cells.end; ++e)
            for (unsigned int a = 0; a < 4; ++a)
              local[cells.point[a][cells.at(e)]] = 0;
          std::vector<double> xyz;
          for (unsigned int p = 0; p < cells.n_points; ++p)
            if (local[p] != unused)
              {
                local[p] = piece.points.size();
                piece.points.push_back(p);
                for (unsigned int c = 0; c < 3; ++c)
                  xyz.push_back(cells.reference_position[3 * p + c]);
              }
          std::vector<unsigned int> tetrahedra;
          for (unsigned int e = piece.cells.begin; e < piece.cells.end; ++e)
            for (unsigned int a = 0; a < 4; ++a)
              tetrahedra.push_back(local[cells.point[a][cells.at(e)]]);
          vtu.push_back(std::make_unique<VtuFile>(xyz, tetrahedra));
          pieces.push_back(std::move(piece));
        }
    }

    const ElasticBodies        &bodies;
    const std::filesystem::path directory;
    const Format                format;
    const double                interval;
    double                      next_time;
    const dealii::MappingFE<3>  mapping;
    /** Whether the system has obstacles to draw (fields/obstacles.vtu). */
    bool has_obstacles = false;
    /** This process and the number of processes: on several, each writes
     * its piece of every body, and the first the .pvtu files and the
     * series. */
    const unsigned int rank, ranks;
    /** Each body's mesh, or this process's piece of it, encoded once
     * (format vtu). */
    std::vector<std::unique_ptr<VtuFile>>       vtu;
    std::vector<Piece>                          pieces;
    std::vector<std::pair<double, std::string>> pvd_records;
    /** Snapshots not yet in solution.pvd, and when it was last written. */
    bool                                  pvd_pending = false;
    std::chrono::steady_clock::time_point pvd_written;

    void
    write_pvd()
    {
      std::ostringstream pvd;
      dealii::DataOutBase::write_pvd_record(pvd, pvd_records);
      write_file_atomically((directory / "solution.pvd").string(), pvd.str());
      pvd_pending = false;
      pvd_written = std::chrono::steady_clock::now();
    }
    std::vector<dealii::XDMFEntry> xdmf_entries;

    /** Format hdf5: a deal.II mesh of the body for DataOut, its cells
     * those of the body in their order, and for each degree of freedom the
     * body's coordinate (3 p + c for component c of point p). */
    dealii::Triangulation<3>  tria;
    dealii::DoFHandler<3>     dof_handler;
    std::vector<unsigned int> coordinate_of_dof;

    void
    make_dof_handler(const P1CellData &cells)
    {
      std::vector<dealii::Point<3>> vertices(cells.n_points);
      for (unsigned int p = 0; p < cells.n_points; ++p)
        for (unsigned int c = 0; c < 3; ++c)
          vertices[p][c] = cells.reference_position[3 * p + c];
      std::vector<dealii::CellData<3>> cell_list(cells.n_cells,
                                                 dealii::CellData<3>(4));
      for (unsigned int e = 0; e < cells.n_cells; ++e)
        for (unsigned int a = 0; a < 4; ++a)
          cell_list[e].vertices[a] = cells.point[a][e];
      tria.create_triangulation(vertices, cell_list, dealii::SubCellData());
      dof_handler.reinit(tria);
      dof_handler.distribute_dofs(
        dealii::FESystem<3>(dealii::FE_SimplexP<3>(1), 3));
      coordinate_of_dof.resize(dof_handler.n_dofs());
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (const unsigned int a : cell->vertex_indices())
          {
            // The cells keep their order and vertices (checked, as the cell
            // fields are written by cell number).
            const unsigned int p = cell->vertex_index(a);
            AssertThrow(p == cells.point[a][cell->active_cell_index()],
                        dealii::ExcInternalError());
            for (unsigned int c = 0; c < 3; ++c)
              coordinate_of_dof[cell->vertex_dof_index(a, c)] = 3 * p + c;
          }
    }
  };



  FieldOutput::FieldOutput(const ElasticBodies &bodies,
                           const std::string   &directory,
                           const Format         format,
                           const double         start_time,
                           const double         interval)
    : implementation(std::make_unique<Implementation>(bodies,
                                                      directory,
                                                      format,
                                                      start_time,
                                                      interval))
  {}



  void
  FieldOutput::start()
  {
    Implementation &self = *implementation;
    std::filesystem::create_directories(self.directory / "fields");
    // The obstacles do not move: one file, listed in every snapshot.
    std::vector<double>       points;
    std::vector<unsigned int> triangles;
    self.bodies.obstacle_surface(points, triangles);
    self.has_obstacles = !triangles.empty();
    if (self.has_obstacles && self.format == Format::vtu && self.rank == 0)
      {
        const std::filesystem::path file =
          self.directory / "fields" / "obstacles.vtu";
        std::ofstream out(file);
        VtuFile(points, triangles, 3).write(out, 0., 0, {}, {});
        out.close();
        if (!out)
          throw std::runtime_error("Field output: cannot write <" +
                                   file.string() + ">.");
      }
    if (implementation->format == Format::hdf5)
      start_mpi();
  }



  void
  FieldOutput::save_state(StateWriter &out) const
  {
    const Implementation &self = *implementation;
    out.put(self.next_time);
    out.put(static_cast<std::uint64_t>(self.pvd_records.size()));
    for (const auto &[time, file] : self.pvd_records)
      {
        out.put(time);
        out.put(file);
      }
  }



  void
  FieldOutput::resume(StateReader &in)
  {
    Implementation &self = *implementation;
    if (self.format == Format::hdf5)
      throw std::runtime_error(
        "Postprocessors/Field output/Format: an HDF5 series cannot be "
        "resumed from a checkpoint; use vtu, or run from the start.");
    start();
    self.next_time = in.get<double>();
    self.pvd_records.resize(in.get<std::uint64_t>());
    for (auto &[time, file] : self.pvd_records)
      {
        time = in.get<double>();
        file = in.get_string();
      }
    if (!self.pvd_records.empty() && self.rank == 0)
      self.write_pvd();
  }



  FieldOutput::~FieldOutput() = default;



  void
  FieldOutput::finish(const TimeLoopResult &result)
  {
    if (result.status != RunStatus::failed && implementation->pvd_pending &&
        implementation->rank == 0)
      implementation->write_pvd();
  }



  bool
  FieldOutput::runs_on_every_rank() const
  {
    return implementation->format == Format::vtu;
  }



  unsigned int
  FieldOutput::n_snapshots() const
  {
    return implementation->format == Format::vtu ?
             implementation->pvd_records.size() :
             implementation->xdmf_entries.size();
  }



  void
  FieldOutput::after_step(const TimeIntegrator &integrator)
  {
    Implementation &self = *implementation;
    while (self.next_time <= integrator.time())
      {
        try
          {
            write(integrator.dense_state(
              std::max(self.next_time, integrator.previous_time())));
          }
        catch (const std::runtime_error &error)
          {
            // A snapshot or the series file could not be written: the run
            // stops with status failed.
            throw OutputFailed(error.what());
          }
        if (!(self.interval > 0.))
          {
            self.next_time = std::numeric_limits<double>::infinity();
            break;
          }
        self.next_time += self.interval;
      }
  }



  void
  FieldOutput::write(const Snapshot &snapshot)
  {
    Implementation    &self     = *implementation;
    const unsigned int n        = n_snapshots();
    const unsigned int n_bodies = self.bodies.n_bodies();
    char               name[64];
    Vector             q, v;
    if (self.format == Format::vtu)
      {
        // One file per body, written in place: a new file that the series
        // lists only once it is complete. A file of an earlier run is
        // removed first: renaming over it or truncating it would make ext4
        // flush the new one to disk (seconds per run on a busy disk).
        std::vector<std::string> files;
        for (unsigned int b = 0; b < n_bodies; ++b)
          {
            const ElasticBody           &body  = self.bodies.body(b);
            const Implementation::Piece &piece = self.pieces[b];
            self.bodies.body_state(snapshot.q, snapshot.v, b, q, v);
            std::vector<double> displacement(q.begin(), q.end()),
              velocity(v.begin(), v.end()), J, W, stress, von_mises;
            for (unsigned int k = 0; k < displacement.size(); ++k)
              displacement[k] -= body.cell_data().reference_position[k];
            body.cell_fields(q, piece.cells, J, W);
            body.cell_stresses(q, piece.cells, stress, von_mises);
            if (n_bodies == 1)
              std::snprintf(name, sizeof(name), "solution-%05u", n);
            else
              std::snprintf(name, sizeof(name), "solution-%05u-%u", n, b + 1);
            const std::string base = name;
            std::vector<VtuFile::Field>
              point_fields = {{"displacement", 3, &displacement},
                              {"velocity", 3, &velocity}},
              cell_fields  = {{"J", 1, &J},
                              {"strain_energy_density", 1, &W},
                              {"cauchy_stress", 9, &stress},
                              {"von_mises_stress", 1, &von_mises}};
            std::string                      file_name = base + ".vtu";
            std::vector<std::vector<double>> piece_values;
            if (self.ranks > 1)
              {
                // This process's piece: its points' values (the cell fields
                // are its cells' already).
                piece_values.reserve(point_fields.size());
                for (VtuFile::Field &field : point_fields)
                  {
                    auto &values = piece_values.emplace_back();
                    for (const unsigned int p : piece.points)
                      for (unsigned int c = 0; c < field.n_components; ++c)
                        values.push_back(
                          (*field.values)[field.n_components * p + c]);
                    field.values = &values;
                  }
                file_name = base + "-p" + std::to_string(self.rank) + ".vtu";
              }
            const std::filesystem::path file =
              self.directory / "fields" / file_name;
            std::filesystem::remove(file);
            std::ofstream out(file);
            self.vtu[b]->write(out, snapshot.t, n, point_fields, cell_fields);
            out.close();
            if (!out)
              throw std::runtime_error("Field output: cannot write <" +
                                       file.string() + ">.");
            if (self.ranks > 1)
              {
                // The first process lists the pieces of all.
                file_name = base + ".pvtu";
                if (self.rank == 0)
                  {
                    std::vector<std::string> piece_files;
                    for (unsigned int r = 0; r < self.ranks; ++r)
                      piece_files.push_back(base + "-p" + std::to_string(r) +
                                            ".vtu");
                    std::ostringstream pvtu;
                    VtuFile::write_parallel(pvtu,
                                            piece_files,
                                            point_fields,
                                            cell_fields);
                    write_file_atomically(
                      (self.directory / "fields" / file_name).string(),
                      pvtu.str());
                  }
              }
            files.push_back(file_name);
          }
        std::string series_entry = "fields/" + files[0];
        if (self.rank > 0)
          {
            // The series is the first process's; the others count the
            // snapshots alike.
            self.pvd_records.emplace_back(snapshot.t, series_entry);
            return;
          }
        if (n_bodies > 1 || self.has_obstacles)
          {
            // The bodies of one snapshot as a multiblock data set.
            std::snprintf(name, sizeof(name), "solution-%05u.vtm", n);
            std::ostringstream vtm;
            vtm << "<?xml version=\"1.0\"?>\n<VTKFile "
                   "type=\"vtkMultiBlockDataSet\" version=\"1.0\" "
                   "byte_order=\"LittleEndian\">\n  <vtkMultiBlockDataSet>\n";
            for (unsigned int b = 0; b < n_bodies; ++b)
              vtm << "    <DataSet index=\"" << b << "\" name=\"body " << b + 1
                  << "\" file=\"" << files[b] << "\"/>\n";
            if (self.has_obstacles)
              vtm << "    <DataSet index=\"" << n_bodies
                  << "\" name=\"obstacles\" file=\"obstacles.vtu\"/>\n";
            vtm << "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
            write_file_atomically((self.directory / "fields" / name).string(),
                                  vtm.str());
            series_entry = std::string("fields/") + name;
          }
        self.pvd_records.emplace_back(snapshot.t, series_entry);
        self.pvd_pending = true;
        if (self.pvd_records.size() == 1 ||
            std::chrono::steady_clock::now() - self.pvd_written >=
              std::chrono::seconds(1))
          self.write_pvd();
        return;
      }

    // HDF5/XDMF through deal.II's DataOut (one body).
    const ElasticBody &body = self.bodies.body(0);
    self.bodies.body_state(snapshot.q, snapshot.v, 0, q, v);
    const std::vector<double> &X = body.cell_data().reference_position;
    dealii::Vector<double>     displacement_vector(q.size()),
      velocity_vector(q.size());
    for (unsigned int k = 0; k < q.size(); ++k)
      {
        const unsigned int i   = self.coordinate_of_dof[k];
        displacement_vector[k] = q[i] - X[i];
        velocity_vector[k]     = v[i];
      }
    std::vector<double> J, W;
    body.cell_fields(q, {0, body.n_cells()}, J, W);
    dealii::Vector<double> cell_J(J.begin(), J.end()),
      cell_W(W.begin(), W.end());
    dealii::DataOut<3> data_out;
    data_out.attach_dof_handler(self.dof_handler);
    const std::vector<
      dealii::DataComponentInterpretation::DataComponentInterpretation>
      vector_field(
        3, dealii::DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(displacement_vector,
                             std::vector<std::string>(3, "displacement"),
                             dealii::DataOut<3>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(velocity_vector,
                             std::vector<std::string>(3, "velocity"),
                             dealii::DataOut<3>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(cell_J, "J", dealii::DataOut<3>::type_cell_data);
    data_out.add_data_vector(cell_W,
                             "strain_energy_density",
                             dealii::DataOut<3>::type_cell_data);
    data_out.build_patches(self.mapping, 1);
    std::snprintf(name, sizeof(name), "fields/solution-%05u.h5", n);
    dealii::DataOutBase::DataOutFilter filter(
      dealii::DataOutBase::DataOutFilterFlags(true, true));
    data_out.write_filtered_data(filter);
    data_out.write_hdf5_parallel(filter,
                                 (self.directory / name).string(),
                                 MPI_COMM_SELF);
    self.xdmf_entries.push_back(
      data_out.create_xdmf_entry(filter, name, snapshot.t, MPI_COMM_SELF));
    const std::string xdmf = (self.directory / "solution.xdmf").string();
    data_out.write_xdmf_file(self.xdmf_entries, xdmf + ".part", MPI_COMM_SELF);
    std::filesystem::rename(xdmf + ".part", xdmf);
  }



  namespace
  {
    void
    declare_field_output_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Field output");
      prm.declare_entry("Interval",
                        "0.1",
                        dealii::Patterns::Double(
                          0., dealii::Patterns::Double::max_double_value),
                        "Write a snapshot every this much simulated time, "
                        "from the start time on; must be positive.");
      prm.declare_entry(
        "Format",
        "vtu",
        dealii::Patterns::Selection("vtu|hdf5"),
        "vtu: fields/solution-NNNNN.vtu and the time series solution.pvd; "
        "hdf5: fields/solution-NNNNN.h5 and solution.xdmf.");
      prm.leave_subsection();
    }

    std::unique_ptr<Postprocessor>
    create_field_output(dealii::ParameterHandler   &prm,
                        const PostprocessorContext &run)
    {
      prm.enter_subsection("Field output");
      const double      interval = prm.get_double("Interval");
      const std::string format   = prm.get("Format");
      prm.leave_subsection();
      const MechanicalSystem &system = run.integrator.mechanical_system();
      const auto *bodies = dynamic_cast<const ElasticBodies *>(&system);
      if (bodies == nullptr)
        throw std::runtime_error("Postprocessors/List: field output: the "
                                 "system <" +
                                 system.name() + "> has no fields to write.");
      if (format == "hdf5" && bodies->n_bodies() > 1)
        throw std::runtime_error(
          "Postprocessors/Field output/Format: hdf5 writes one body, and the "
          "system <" +
          system.name() + "> has " + std::to_string(bodies->n_bodies()) +
          "; choose vtu.");
      if (!(interval > 0.))
        throw std::runtime_error(
          "Postprocessors/Field output/Interval: must be positive.");
      if ((run.end_time - run.start_time) / interval > 1e5)
        throw std::runtime_error(
          "Postprocessors/Field output/Interval: would write more than "
          "100000 snapshots over the run; choose a larger interval.");
      return std::make_unique<FieldOutput>(*bodies,
                                           run.output_directory,
                                           format == "hdf5" ?
                                             FieldOutput::Format::hdf5 :
                                             FieldOutput::Format::vtu,
                                           run.start_time,
                                           interval);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_POSTPROCESSOR(
  "field output",
  "snapshots of an elastic body's fields for ParaView (displacement, "
  "velocity, J, strain energy density) in fields/, with a time series file "
  "(subsection Field output).",
  estep::declare_field_output_parameters,
  estep::create_field_output)
