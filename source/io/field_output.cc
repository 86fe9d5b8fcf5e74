#include <deal.II/base/parameter_handler.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/json_writer.h>
#include <estep/fem/elastic_body.h>
#include <estep/io/field_output.h>
#include <estep/io/hdf5_file.h>
#include <estep/io/vtu_file.h>
#include <estep/io/xdmf_series.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    /** The fields of a snapshot: of every body in vtu and in HDF5. */
    const std::vector<XdmfSeries::Field> snapshot_fields = {
      {"displacement", 3, false},
      {"velocity", 3, false},
      {"J", 1, true},
      {"strain_energy_density", 1, true},
      {"cauchy_stress", 9, true},
      {"von_mises_stress", 1, true}};

    /** The message of @p error, a file that could not be written, as
     * field output's. */
    std::string
    field_output_message(const std::runtime_error &error)
    {
      std::string message = error.what();
      if (!message.empty() && message.back() == '.')
        message.pop_back();
      return "Field output: " + message + ".";
    }

    /** The files of a snapshot being written: removed, should it fail
     * (a full disk), so that no partial file stays behind. */
    class UnfinishedFiles
    {
    public:
      void
      add(const std::filesystem::path &file)
      {
        files.push_back(file);
      }

      /** The snapshot is complete: the files stay. */
      void
      keep()
      {
        files.clear();
      }

      ~UnfinishedFiles()
      {
        std::error_code ignored;
        for (const std::filesystem::path &file : files)
          std::filesystem::remove(file, ignored);
      }

    private:
      std::vector<std::filesystem::path> files;
    };

    /** The HDF5 group of body @p b. */
    std::string
    body_group(const unsigned int b)
    {
      return "body" + std::to_string(b + 1);
    }
  } // namespace



  struct FieldOutput::Implementation
  {
    /** This process's piece of a body: the cells of its blocks (all on one
     * process), and the points whose values it writes: in vtu, on several
     * processes, those of its cells; in HDF5, a balanced share of all. */
    struct Piece
    {
      BlockRange                cells;
      std::vector<unsigned int> points;
      BlockRange                point_rows;
    };

    Implementation(const ElasticBodies &bodies,
                   const std::string   &directory,
                   const Format         format,
                   const double         start_time,
                   const double         interval,
                   const double         end_time)
      : bodies(bodies)
      , directory(directory)
      , format(format)
      , start_time(start_time)
      , interval(interval)
      , end_time(end_time)
      , next_time(start_time)
      , rank(this_rank())
      , ranks(rank_count())
    {
      for (unsigned int b = 0; b < bodies.n_bodies(); ++b)
        {
          const P1CellData &cells = bodies.body(b).cell_data();
          Piece             piece;
          piece.cells      = rank_cells(cells.n_cells, rank);
          piece.point_rows = rank_blocks(cells.n_points, rank);
          if (format == Format::hdf5)
            {
              pieces.push_back(std::move(piece));
              continue;
            }
          if (ranks == 1)
            {
              std::vector<unsigned int> tetrahedra(4 *
                                                   std::size_t(cells.n_cells));
              for (unsigned int e = 0; e < cells.n_cells; ++e)
                for (unsigned int a = 0; a < 4; ++a)
                  tetrahedra[4 * e + a] = cells.point[a][cells.at(e)];
              vtu.push_back(std::make_unique<VtuFile>(cells.reference_position,
                                                      tetrahedra));
              pieces.push_back(std::move(piece));
              continue;
            }
          // This process's piece: the cells of its blocks and their points.
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
    const double                start_time, interval, end_time;
    /** The next snapshot's time on the grid start_time + k interval, and
     * its k (each time computed from k, so that no rounding accumulates). */
    double        next_time;
    std::uint64_t next_index = 0;

    /** Move next_time to the grid's next time. */
    void
    advance_grid()
    {
      ++next_index;
      next_time = interval > 0. ?
                    start_time + static_cast<double>(next_index) * interval :
                    std::numeric_limits<double>::infinity();
    }
    /** Whether the system has obstacles to draw. */
    bool has_obstacles = false;
    /** This process and the number of processes: on several, each writes
     * its piece of every body, and the first the series (and in vtu the
     * .pvtu files). */
    const unsigned int rank, ranks;
    /** Each body's mesh, or this process's piece of it, encoded once
     * (format vtu). */
    std::vector<std::unique_ptr<VtuFile>> vtu;
    std::vector<Piece>                    pieces;
    /** The time and the file (relative to the output directory) of every
     * snapshot written, and in HDF5 the layout of the files. */
    std::vector<std::pair<double, std::string>> series;
    XdmfSeries                                  xdmf;
    /** Snapshots not yet in the series file, and when it was last written. */
    bool                                  series_pending = false;
    std::chrono::steady_clock::time_point series_written;

    /** Rewrites solution.pvd or solution.xdmf (first process only). */
    void
    write_series()
    {
      if (format == Format::vtu)
        {
          std::ostringstream pvd;
          VtuFile::write_series(pvd, series);
          write_file_atomically((directory / "solution.pvd").string(),
                                pvd.str());
        }
      else
        write_file_atomically((directory / "solution.xdmf").string(),
                              xdmf.text(series));
      series_pending = false;
      series_written = std::chrono::steady_clock::now();
    }

    /** Format hdf5: fields/mesh.h5, every process its rows, with the
     * bodies' points and cells and the obstacles' triangles. */
    void
    write_hdf5_mesh(const std::vector<double>       &obstacle_points,
                    const std::vector<unsigned int> &obstacle_triangles)
    {
      xdmf.mesh_file = "fields/mesh.h5";
      xdmf.fields    = snapshot_fields;
      xdmf.meshes.clear();
      const std::filesystem::path file = directory / xdmf.mesh_file;
      const std::string           part = file.string() + ".part";
      UnfinishedFiles             unfinished;
      unfinished.add(part);
      Hdf5File mesh(part);
      for (unsigned int b = 0; b < bodies.n_bodies(); ++b)
        {
          const P1CellData &cells = bodies.body(b).cell_data();
          const Piece      &piece = pieces[b];
          const std::string group = body_group(b);
          mesh.write(
            group + "/points",
            cells.n_points,
            3,
            piece.point_rows.begin,
            std::vector<double>(cells.reference_position.begin() +
                                  3 * std::size_t(piece.point_rows.begin),
                                cells.reference_position.begin() +
                                  3 * std::size_t(piece.point_rows.end)));
          std::vector<unsigned int> tetrahedra;
          for (unsigned int e = piece.cells.begin; e < piece.cells.end; ++e)
            for (unsigned int a = 0; a < 4; ++a)
              tetrahedra.push_back(cells.point[a][cells.at(e)]);
          mesh.write(
            group + "/cells", cells.n_cells, 4, piece.cells.begin, tetrahedra);
          xdmf.meshes.push_back(
            {bodies.n_bodies() == 1 ? "body" : "body " + std::to_string(b + 1),
             group,
             cells.n_points,
             cells.n_cells,
             4,
             true});
        }
      if (has_obstacles)
        {
          // Small, and the same on every process: the first writes them.
          const std::size_t n_points    = obstacle_points.size() / 3,
                            n_triangles = obstacle_triangles.size() / 3;
          mesh.write("obstacles/points",
                     n_points,
                     3,
                     0,
                     rank == 0 ? obstacle_points : std::vector<double>());
          mesh.write("obstacles/cells",
                     n_triangles,
                     3,
                     0,
                     rank == 0 ? obstacle_triangles :
                                 std::vector<unsigned int>());
          xdmf.meshes.push_back(
            {"obstacles", "obstacles", n_points, n_triangles, 3, false});
        }
      mesh.close();
      unfinished.keep();
      if (rank == 0)
        std::filesystem::rename(part, file);
    }
  };



  FieldOutput::FieldOutput(const ElasticBodies &bodies,
                           const std::string   &directory,
                           const Format         format,
                           const double         start_time,
                           const double         interval,
                           const double         end_time)
    : implementation(std::make_unique<Implementation>(bodies,
                                                      directory,
                                                      format,
                                                      start_time,
                                                      interval,
                                                      end_time))
  {}



  void
  FieldOutput::start()
  {
    Implementation &self = *implementation;
    // The obstacles do not move: one file, listed in every snapshot.
    std::vector<double>       points;
    std::vector<unsigned int> triangles;
    self.bodies.obstacle_surface(points, triangles);
    self.has_obstacles = !triangles.empty();
    try
      {
        const std::filesystem::path fields = self.directory / "fields";
        std::error_code             failure;
        std::filesystem::create_directories(fields, failure);
        if (failure)
          throw std::runtime_error("cannot create the directory <" +
                                   fields.string() + ">: " + failure.message());
        if (self.format == Format::hdf5)
          self.write_hdf5_mesh(points, triangles);
        else if (self.has_obstacles && self.rank == 0)
          {
            std::ostringstream out;
            VtuFile(points, triangles, 3).write(out, 0., 0, {}, {});
            write_file_atomically(
              (self.directory / "fields" / "obstacles.vtu").string(),
              out.str());
          }
      }
    catch (const std::runtime_error &error)
      {
        throw std::runtime_error(field_output_message(error));
      }
  }



  void
  FieldOutput::save_state(StateWriter &out) const
  {
    const Implementation &self = *implementation;
    out.put(self.next_time);
    out.put(static_cast<std::uint64_t>(self.series.size()));
    for (const auto &[time, file] : self.series)
      {
        out.put(time);
        out.put(file);
      }
  }



  void
  FieldOutput::resume(StateReader &in)
  {
    Implementation &self = *implementation;
    self.next_time       = in.get<double>();
    if (self.interval > 0. && std::isfinite(self.next_time))
      self.next_index = static_cast<std::uint64_t>(
        std::llround((self.next_time - self.start_time) / self.interval));
    self.series.resize(in.get<std::uint64_t>());
    for (auto &[time, file] : self.series)
      {
        time = in.get<double>();
        file = in.get_string();
      }
    std::error_code failure;
    // The snapshots the series lists must still be there: a series that
    // goes on would list missing files. (Every process looks, and so
    // throws alike.)
    for (const auto &[time, file] : self.series)
      if (!std::filesystem::is_regular_file(self.directory / file))
        {
          std::ostringstream message;
          message << "Cannot resume the field output: its snapshot <"
                  << (self.directory / file).string() << "> of t = " << time
                  << " is missing.";
          throw std::runtime_error(message.str());
        }
    if (!self.series.empty())
      {
        const bool hdf5_series =
          std::filesystem::path(self.series[0].second).extension() == ".h5";
        if (hdf5_series != (self.format == Format::hdf5))
          throw std::runtime_error(
            std::string("Postprocessors/Field output/Format: the checkpoint's "
                        "series is in ") +
            (hdf5_series ? "hdf5" : "vtu") + "; resume with that format.");
      }
    // Snapshots written after the checkpoint by the run that stopped
    // (killed before its next checkpoint) are not in the series: the first
    // process removes them, before any process writes the next one.
    if (self.rank == 0)
      for (const auto &entry : std::filesystem::directory_iterator(
             self.directory / "fields",
             std::filesystem::directory_options::skip_permission_denied,
             failure))
        {
          const std::string name = entry.path().filename().string();
          unsigned int      index;
          if (std::sscanf(name.c_str(), "solution-%5u", &index) == 1 &&
              index >= self.series.size())
            std::filesystem::remove(entry.path(), failure);
        }
    largest_over_ranks(0);
    start();
    if (!self.series.empty() && self.rank == 0)
      self.write_series();
  }



  FieldOutput::~FieldOutput() = default;



  void
  FieldOutput::finish(const TimeLoopResult &)
  {
    // Also after a failure: every snapshot the series holds was written
    // whole (and agreed by every process), and one written since the last
    // rewrite would be left out of it.
    if (implementation->series_pending && implementation->rank == 0)
      implementation->write_series();
  }



  bool
  FieldOutput::runs_on_every_rank() const
  {
    return true;
  }



  unsigned int
  FieldOutput::n_snapshots() const
  {
    return implementation->series.size();
  }



  void
  FieldOutput::after_step(const TimeIntegrator &integrator)
  {
    Implementation &self     = *implementation;
    const auto      write_at = [&](const double t) {
      try
        {
          write(
            integrator.dense_state(std::max(t, integrator.previous_time())));
        }
      catch (const std::runtime_error &error)
        {
          // A snapshot or the series file could not be written: the run
          // stops with status failed.
          throw OutputFailed(field_output_message(error));
        }
    };
    while (self.next_time <= integrator.time())
      {
        write_at(self.next_time);
        self.advance_grid();
      }
    // The end time gets a snapshot too, as history.csv gets a row there,
    // unless the last snapshot lies within round-off of it; one that stands
    // in for the next time of the grid takes its place (a resumed run with a
    // later end time goes on from the one after).
    const double t_end = self.end_time;
    if (integrator.time() < t_end)
      return;
    // Of the size of the times compared (not of the interval, which may
    // be far longer than the run).
    const double round_off =
      1e-12 * std::max(std::abs(t_end), std::abs(self.start_time));
    if (!self.series.empty() && self.series.back().first >= t_end - round_off)
      return;
    write_at(t_end);
    if (self.next_time - t_end <= round_off)
      self.advance_grid();
  }



  void
  FieldOutput::write(const Snapshot &snapshot)
  {
    Implementation    &self     = *implementation;
    const unsigned int n        = n_snapshots();
    const unsigned int n_bodies = self.bodies.n_bodies();
    char               name[64];
    std::snprintf(name, sizeof(name), "solution-%05u", n);
    const std::string         snapshot_name = name;
    UnfinishedFiles           unfinished;
    std::unique_ptr<Hdf5File> hdf5;
    if (self.format == Format::hdf5)
      {
        const std::filesystem::path file =
          self.directory / "fields" / (snapshot_name + ".h5");
        unfinished.add(file);
        hdf5 = std::make_unique<Hdf5File>(file.string());
        hdf5->write_attribute("time", snapshot.t);
      }
    // In vtu, one file per body, written in place: a new file that the
    // series lists only once it is complete. A file of an earlier run is
    // removed first: renaming over it or truncating it would make ext4 flush
    // the new one to disk (seconds per run on a busy disk).
    std::vector<std::string> files;
    // The .pvtu files joining the processes' pieces (the first process's).
    std::vector<std::pair<std::filesystem::path, std::string>> joins;
    std::string                                                failure;
    Vector                                                     q, v;
    try
      {
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
            // In the order of snapshot_fields.
            const std::vector<double> *values[] = {
              &displacement, &velocity, &J, &W, &stress, &von_mises};
            std::vector<VtuFile::Field> point_fields, cell_fields;
            for (unsigned int i = 0; i < snapshot_fields.size(); ++i)
              {
                const XdmfSeries::Field &field = snapshot_fields[i];
                (field.on_cells ? cell_fields : point_fields)
                  .push_back({field.name, field.n_components, values[i]});
              }
            if (hdf5)
              {
                // This process's rows: its share of the points, its cells.
                const std::string group = body_group(b);
                for (const VtuFile::Field &field : point_fields)
                  hdf5->write(group + "/" + field.name,
                              body.cell_data().n_points,
                              field.n_components,
                              piece.point_rows.begin,
                              std::vector<double>(
                                field.values->begin() +
                                  field.n_components * piece.point_rows.begin,
                                field.values->begin() +
                                  field.n_components * piece.point_rows.end));
                for (const VtuFile::Field &field : cell_fields)
                  hdf5->write(group + "/" + field.name,
                              body.n_cells(),
                              field.n_components,
                              piece.cells.begin,
                              *field.values);
                continue;
              }
            const std::string base =
              n_bodies == 1 ? snapshot_name :
                              snapshot_name + "-" + std::to_string(b + 1);
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
            // An earlier file goes first; if it cannot (the directory is
            // gone), writing the new one fails below and says so.
            std::error_code not_removed;
            std::filesystem::remove(file, not_removed);
            unfinished.add(file);
            std::ofstream out(file);
            if (!out)
              throw std::runtime_error("cannot write <" + file.string() +
                                       ">: " + std::strerror(errno));
            self.vtu[b]->write(out, snapshot.t, n, point_fields, cell_fields);
            out.close();
            if (!out)
              throw std::runtime_error("cannot write <" + file.string() + ">");
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
                    joins.emplace_back(self.directory / "fields" / file_name,
                                       pvtu.str());
                  }
              }
            files.push_back(file_name);
          }
        if (hdf5)
          hdf5->close();
      }
    catch (const std::runtime_error &error)
      {
        failure = error.what();
      }
    // On several processes a snapshot is whole only if every process wrote
    // its part: otherwise each removes its own (unfinished), the series does
    // not list it, and every process knows why.
    if (self.ranks > 1)
      failure = first_message_over_ranks(failure);
    if (!failure.empty())
      throw std::runtime_error(failure);
    for (const auto &[file, text] : joins)
      {
        unfinished.add(file);
        write_file_atomically(file.string(), text);
      }
    unfinished.keep();
    std::string series_entry;
    if (hdf5)
      series_entry = "fields/" + snapshot_name + ".h5";
    else if (n_bodies > 1 || self.has_obstacles)
      {
        // The bodies of one snapshot as a multiblock data set.
        series_entry = "fields/" + snapshot_name + ".vtm";
        if (self.rank == 0)
          {
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
            write_file_atomically((self.directory / series_entry).string(),
                                  vtm.str());
          }
      }
    else
      series_entry = "fields/" + files[0];
    self.series.emplace_back(snapshot.t, series_entry);
    if (self.rank > 0)
      return; // the series is the first process's; the others count alike
    self.series_pending = true;
    if (self.series.size() == 1 ||
        std::chrono::steady_clock::now() - self.series_written >=
          std::chrono::seconds(1))
      self.write_series();
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
                        "from the start time on, and one at the end time; "
                        "must be positive.");
      prm.declare_entry(
        "Format",
        "vtu",
        dealii::Patterns::Selection("vtu|hdf5"),
        "vtu: fields/solution-NNNNN.vtu (one file per body, joined by a .vtm "
        "file; on several MPI processes one piece per process, joined by a "
        ".pvtu file) and the time series solution.pvd. hdf5: the mesh in "
        "fields/mesh.h5, the fields of each snapshot in "
        "fields/solution-NNNNN.h5 (a group per body: body1, body2, ...; "
        "written by every process together), and the time series "
        "solution.xdmf.");
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
                                           interval,
                                           run.end_time);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_POSTPROCESSOR(
  "field output",
  "snapshots of an elastic body's fields for ParaView (displacement, "
  "velocity, J, strain energy density, Cauchy stress, von Mises stress) in "
  "fields/, with a time series file (subsection Field output).",
  estep::declare_field_output_parameters,
  estep::create_field_output)
