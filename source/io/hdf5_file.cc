#include <estep/base/distributed_blocks.h>
#include <estep/io/hdf5_file.h>

#include <hdf5.h>
#include <mpi.h>

#include <cstdio>
#include <stdexcept>
#include <type_traits>

namespace estep
{
  namespace
  {
    /** Closes an HDF5 object when it leaves scope. */
    class Handle
    {
    public:
      Handle(const hid_t id, herr_t (*const close)(hid_t))
        : id(id)
        , close_function(close)
      {}
      ~Handle()
      {
        if (id >= 0)
          close_function(id);
      }
      Handle(const Handle &) = delete;
      Handle &
      operator=(const Handle &) = delete;

      operator hid_t() const
      {
        return id;
      }

    private:
      const hid_t id;
      herr_t (*const close_function)(hid_t);
    };
  } // namespace



  Hdf5File::Hdf5File(const std::string &path)
    : path(path)
    , parallel(rank_count() > 1)
  {
    // Without HDF5's clean-up at exit: a file that a failed write left open
    // would be flushed again there, and the process would crash instead of
    // ending with its message. A completed file is closed by close().
    [[maybe_unused]] static const herr_t without_clean_up_at_exit =
      H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    // A file of an earlier run is removed first: truncating it would make
    // ext4 flush the new one to disk (seconds per run on a busy disk).
    if (this_rank() == 0)
      std::remove(path.c_str());
    if (parallel)
      MPI_Barrier(MPI_COMM_WORLD);
    const Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    if (parallel)
      H5Pset_fapl_mpio(access, MPI_COMM_WORLD, MPI_INFO_NULL);
    file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access);
    if (file < 0)
      throw std::runtime_error("cannot create the HDF5 file <" + path + ">");
  }



  Hdf5File::~Hdf5File()
  {
    // Left after an error: on several processes closing is collective, and
    // the others, which may not have met the error, may never come to it (a
    // failed output ends every process).
    if (file >= 0 && !parallel)
      H5Fclose(file);
  }



  void
  Hdf5File::make_groups_of(const std::string &name)
  {
    // Without the times of their making, as the datasets: two files of the
    // same data are the same bytes.
    std::size_t slash = name.find('/');
    while (slash != std::string::npos)
      {
        const std::string group = name.substr(0, slash);
        slash                   = name.find('/', slash + 1);
        if (H5Lexists(file, group.c_str(), H5P_DEFAULT) > 0)
          continue;
        const Handle properties(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
        H5Pset_obj_track_times(properties, false);
        const Handle made(
          H5Gcreate2(file, group.c_str(), H5P_DEFAULT, properties, H5P_DEFAULT),
          H5Gclose);
      }
  }



  template <typename T>
  void
  Hdf5File::write(const std::string    &name,
                  const std::size_t     n_rows,
                  const unsigned int    n_columns,
                  const std::size_t     first_row,
                  const std::vector<T> &values)
  {
    constexpr bool indices = std::is_same_v<T, unsigned int>;
    static_assert(indices || std::is_same_v<T, double>);
    const hsize_t my_rows = values.size() / n_columns;
    if (my_rows * n_columns != values.size() || first_row + my_rows > n_rows)
      throw std::logic_error("Hdf5File: rows of <" + name +
                             "> out of range in <" + path + ">");
    const int     n_dimensions = n_columns == 1 ? 1 : 2;
    const hsize_t size[2]      = {n_rows, n_columns};
    const Handle space(H5Screate_simple(n_dimensions, size, nullptr), H5Sclose);
    make_groups_of(name);
    const Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_obj_track_times(properties, false);
    const Handle  dataset(H5Dcreate2(file,
                                    name.c_str(),
                                    indices ? H5T_STD_U32LE : H5T_IEEE_F64LE,
                                    space,
                                    H5P_DEFAULT,
                                    properties,
                                    H5P_DEFAULT),
                         H5Dclose);
    const hsize_t start[2] = {first_row, 0}, count[2] = {my_rows, n_columns};
    const Handle  memory(H5Screate_simple(n_dimensions, count, nullptr),
                        H5Sclose);
    if (my_rows == 0)
      {
        H5Sselect_none(space);
        H5Sselect_none(memory);
      }
    else
      H5Sselect_hyperslab(
        space, H5S_SELECT_SET, start, nullptr, count, nullptr);
    const Handle transfer(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
    if (parallel)
      H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE);
    if (dataset < 0 || H5Dwrite(dataset,
                                indices ? H5T_NATIVE_UINT : H5T_NATIVE_DOUBLE,
                                memory,
                                space,
                                transfer,
                                values.data()) < 0)
      throw std::runtime_error("cannot write <" + name +
                               "> into the HDF5 file <" + path + ">");
  }



  template void
  Hdf5File::write(const std::string &,
                  std::size_t,
                  unsigned int,
                  std::size_t,
                  const std::vector<double> &);
  template void
  Hdf5File::write(const std::string &,
                  std::size_t,
                  unsigned int,
                  std::size_t,
                  const std::vector<unsigned int> &);



  void
  Hdf5File::write_attribute(const std::string &name, const double value)
  {
    const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    const Handle attribute(
      H5Acreate2(
        file, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
    if (attribute < 0 || H5Awrite(attribute, H5T_NATIVE_DOUBLE, &value) < 0)
      throw std::runtime_error("cannot write the attribute <" + name +
                               "> into the HDF5 file <" + path + ">");
  }



  void
  Hdf5File::close()
  {
    const herr_t status = H5Fclose(file);
    file                = -1;
    if (status < 0)
      throw std::runtime_error("cannot complete the HDF5 file <" + path + ">");
  }
} // namespace estep
