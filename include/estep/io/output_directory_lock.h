#ifndef estep_io_output_directory_lock_h
#define estep_io_output_directory_lock_h

#include <filesystem>

namespace estep
{
  /**
   * An exclusive lock on an output directory, held while the object lives:
   * a second run into the same directory (a job started again while the
   * first still runs) is refused instead of writing its outputs into the
   * first one's. The lock is flock() on the file `.estep.lock` in the
   * directory, which stays there; the system releases it when the process
   * ends, however it ends (SIGKILL too), so a file left behind locks nothing.
   * On a network file system the lock is as good as its support of flock()
   * (NFS emulates it with POSIX record locks).
   */
  class OutputDirectoryLock
  {
  public:
    /** Takes the lock of the existing directory @p directory; throws
     * std::runtime_error naming the directory if another process holds it,
     * or if the lock file cannot be made. */
    explicit OutputDirectoryLock(const std::filesystem::path &directory);

    ~OutputDirectoryLock();

    OutputDirectoryLock(const OutputDirectoryLock &) = delete;
    OutputDirectoryLock &
    operator=(const OutputDirectoryLock &) = delete;

  private:
    int file_descriptor;
  };
} // namespace estep

#endif
