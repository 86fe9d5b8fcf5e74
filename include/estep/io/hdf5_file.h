#ifndef estep_io_hdf5_file_h
#define estep_io_hdf5_file_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace estep
{
  /**
   * An HDF5 file of two-dimensional datasets (rows of a fixed number of
   * columns, e.g. one row of x, y, z per point), written by every MPI process
   * together: each process writes its own rows of each dataset, and the
   * datasets are the same, to the last bit, however the rows are shared
   * (the layout of the file may differ). No times are stored: two files of
   * the same data written alike are the same bytes.
   * On one process (or without MPI) it is an ordinary serial file.
   *
   * Every member function is collective over the processes of the run (each
   * must call it with the same names and sizes). A failure of the HDF5
   * library throws std::runtime_error naming the file; HDF5's own error
   * printing is turned off.
   */
  class Hdf5File
  {
  public:
    /** Creates @p path, removing a file of that name first. */
    explicit Hdf5File(const std::string &path);

    /** Closes the file if close() was not called, on one process (errors
     * are ignored); on several it is left open: this is an error path, and
     * closing is collective. */
    ~Hdf5File();

    Hdf5File(const Hdf5File &) = delete;
    Hdf5File &
    operator=(const Hdf5File &) = delete;

    /**
     * Writes the dataset @p name ("group/name" makes the group) of
     * @p n_rows rows of @p n_columns values, of which this process gives rows
     * [first_row, first_row + values.size() / n_columns), row-major.
     * T is double (stored as 64-bit IEEE numbers) or unsigned int (indices,
     * stored as 32-bit unsigned integers). One column makes a
     * one-dimensional dataset.
     */
    template <typename T>
    void
    write(const std::string    &name,
          const std::size_t     n_rows,
          const unsigned int    n_columns,
          const std::size_t     first_row,
          const std::vector<T> &values);

    /** A double attribute @p name of the file (e.g. the time). */
    void
    write_attribute(const std::string &name, const double value);

    /** Closes the file; throws if its last writes fail. */
    void
    close();

  private:
    /** Makes the groups of the path @p name that do not exist yet. */
    void
    make_groups_of(const std::string &name);

    std::string  path;
    std::int64_t file = -1; // an hid_t, kept out of this header
    bool         parallel;
  };
} // namespace estep

#endif
