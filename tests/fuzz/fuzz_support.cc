#include "fuzz_support.h"

#include <deal.II/base/exceptions.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace estep_fuzz
{
  namespace
  {
    // Created on first use, removed at exit (a pointer, so that no
    // destructor runs before the removal).
    const std::filesystem::path &
    scratch_directory()
    {
      static const std::filesystem::path *const directory = [] {
        const auto path = new std::filesystem::path(
          std::filesystem::temp_directory_path() /
          ("estep-fuzz-" + std::to_string(::getpid())));
        std::filesystem::create_directories(*path);
        std::atexit([] {
          std::error_code ignored;
          std::filesystem::remove_all(scratch_directory(), ignored);
        });
        return path;
      }();
      return *directory;
    }
  } // namespace



  std::string
  scratch_file(const std::string &name)
  {
    const std::filesystem::path path = scratch_directory() / name;
    std::filesystem::create_directories(path.parent_path());
    return path.string();
  }



  void
  write_file(const std::string  &name,
             const std::uint8_t *data,
             const std::size_t   size)
  {
    std::ofstream out(name, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(data),
              static_cast<std::streamsize>(size));
    if (!out)
      {
        std::cerr << "fuzz driver: cannot write " << name << '\n';
        std::abort();
      }
  }



  void
  initialize()
  {
    dealii::deal_II_exceptions::disable_abort_on_exception();
    dealii::deal_II_exceptions::suppress_stacktrace_in_exceptions();
  }



  void
  check_rejection(const std::exception &error)
  {
    const std::string message = error.what();
    if (message.find_first_not_of(" \t\r\n") == std::string::npos)
      {
        std::cerr << "fuzz driver: an input was rejected by an exception "
                     "without a message\n";
        std::abort();
      }
  }
} // namespace estep_fuzz
