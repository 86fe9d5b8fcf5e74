#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <estep/fem/elastic_body.h>
#include <estep/io/field_output.h>
#include <estep/io/json_writer.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace estep
{
  struct FieldOutput::Implementation
  {
    Implementation(const ElasticBody &body,
                   const std::string &directory,
                   const Format       format,
                   const double       start_time,
                   const double       interval)
      : body(body)
      , directory(directory)
      , format(format)
      , interval(interval)
      , next_time(start_time)
      , mapping(dealii::FE_SimplexP<3>(1))
    {}

    const ElasticBody                          &body;
    const std::filesystem::path                 directory;
    const Format                                format;
    const double                                interval;
    double                                      next_time;
    const dealii::MappingFE<3>                  mapping;
    std::vector<std::pair<double, std::string>> pvd_records;
    std::vector<dealii::XDMFEntry>              xdmf_entries;
  };



  FieldOutput::FieldOutput(const ElasticBody &body,
                           const std::string &directory,
                           const Format       format,
                           const double       start_time,
                           const double       interval)
    : implementation(std::make_unique<Implementation>(body,
                                                      directory,
                                                      format,
                                                      start_time,
                                                      interval))
  {
    std::filesystem::create_directories(implementation->directory / "fields");
  }



  FieldOutput::~FieldOutput() = default;



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
        write(integrator.dense_output(
          std::max(self.next_time, integrator.previous_time())));
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
    Implementation              &self      = *implementation;
    const ElasticBody           &body      = self.body;
    const dealii::Vector<double> reference = body.reference_configuration();

    dealii::Vector<double> displacement(snapshot.q);
    displacement -= reference;
    dealii::Vector<double> velocity(snapshot.v);
    std::vector<double>    J, W;
    body.cell_fields(snapshot.q, J, W);
    dealii::Vector<double> cell_J(J.begin(), J.end()),
      cell_W(W.begin(), W.end());

    dealii::DataOut<3> data_out;
    data_out.attach_dof_handler(body.dof_handler());
    const std::vector<
      dealii::DataComponentInterpretation::DataComponentInterpretation>
      vector_field(
        3, dealii::DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(displacement,
                             std::vector<std::string>(3, "displacement"),
                             dealii::DataOut<3>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(velocity,
                             std::vector<std::string>(3, "velocity"),
                             dealii::DataOut<3>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(cell_J, "J", dealii::DataOut<3>::type_cell_data);
    data_out.add_data_vector(cell_W,
                             "strain_energy_density",
                             dealii::DataOut<3>::type_cell_data);
    data_out.build_patches(self.mapping, 1);

    const unsigned int n = n_snapshots();
    char               name[64];
    if (self.format == Format::vtu)
      {
        std::snprintf(name, sizeof(name), "fields/solution-%05u.vtu", n);
        dealii::DataOutBase::VtkFlags flags;
        flags.time  = snapshot.t;
        flags.cycle = n;
        // deal.II's default, best compression, costs ten times the rest of a
        // snapshot; best speed writes files about a third larger.
        flags.compression_level = dealii::DataOutBase::VtkFlags::best_speed;
        data_out.set_flags(flags);
        {
          std::ofstream out(self.directory / name);
          data_out.write_vtu(out);
        }
        self.pvd_records.emplace_back(snapshot.t, name);
        std::ostringstream pvd;
        dealii::DataOutBase::write_pvd_record(pvd, self.pvd_records);
        write_file_atomically((self.directory / "solution.pvd").string(),
                              pvd.str());
      }
    else
      {
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
        data_out.write_xdmf_file(self.xdmf_entries,
                                 xdmf + ".part",
                                 MPI_COMM_SELF);
        std::filesystem::rename(xdmf + ".part", xdmf);
      }
  }
} // namespace estep
