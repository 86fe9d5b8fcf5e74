#include <estep/io/output_directory_lock.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace estep
{
  OutputDirectoryLock::OutputDirectoryLock(
    const std::filesystem::path &directory)
  {
    const std::filesystem::path file = directory / ".estep.lock";
    file_descriptor = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (file_descriptor < 0)
      throw std::runtime_error("cannot make the lock file <" + file.string() +
                               ">: " + std::strerror(errno));
    if (::flock(file_descriptor, LOCK_EX | LOCK_NB) != 0)
      {
        const int error = errno;
        ::close(file_descriptor);
        if (error == EWOULDBLOCK)
          throw std::runtime_error(
            "the output directory <" + directory.string() +
            "> is in use by another estep run (it holds <" + file.string() +
            ">): wait for that run to end, or choose another Output "
            "directory.");
        throw std::runtime_error("cannot lock <" + file.string() +
                                 ">: " + std::strerror(error));
      }
  }



  OutputDirectoryLock::~OutputDirectoryLock()
  {
    ::close(file_descriptor); // releases the lock
  }
} // namespace estep
