#include <estep/base/checksum.h>
#include <estep/io/checkpoint.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace estep
{
  namespace
  {
    /** The first bytes of a checkpoint: the format and its version. */
    const std::string magic = "estep checkpoint 5\n";

    /** The checksum of @p bytes: enough to notice a damaged file. */
    std::uint64_t
    checksum_of(const std::string &bytes)
    {
      return checksum(bytes.data(), bytes.size());
    }

    /** Write @p bytes to @p file and flush them to the disk. */
    void
    write_durably(const std::string &file, const std::string &bytes)
    {
      int       error = 0;
      const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0)
        error = errno;
      for (std::size_t done = 0; error == 0 && done < bytes.size();)
        {
          const ssize_t n =
            ::write(fd, bytes.data() + done, bytes.size() - done);
          if (n > 0)
            done += static_cast<std::size_t>(n);
          else if (n < 0 && errno != EINTR)
            error = errno;
        }
      if (error == 0 && ::fsync(fd) != 0)
        error = errno;
      if (fd >= 0 && ::close(fd) != 0 && error == 0)
        error = errno;
      if (error != 0)
        throw OutputFailed("Writing the checkpoint <" + file +
                           "> failed: " + std::strerror(error) + ".");
    }



    /**
     * The entries of a ParameterHandler's PRM text as "Section/Entry = value"
     * lines, without those a resumed run may change.
     */
    std::vector<std::string>
    fixed_entries(const std::string &parameters)
    {
      std::vector<std::string> sections, entries;
      std::istringstream       in(parameters);
      for (std::string line; std::getline(in, line);)
        {
          const auto first = line.find_first_not_of(" \t");
          if (first == std::string::npos || line[first] == '#')
            continue;
          line = line.substr(first);
          if (line.rfind("subsection ", 0) == 0)
            sections.push_back(line.substr(11));
          else if (line == "end")
            {
              if (!sections.empty())
                sections.pop_back();
            }
          else if (line.rfind("set ", 0) == 0)
            {
              std::string path;
              for (const std::string &section : sections)
                path += section + "/";
              const std::string entry = line.substr(4);
              const std::string name  = entry.substr(0, entry.find('='));
              path += name.substr(0, name.find_last_not_of(' ') + 1);
              if (path != "Output directory" && path != "Threads" &&
                  path != "Time integration/End time" &&
                  path != "Output/Checkpoint interval" &&
                  path != "Output/Checkpoint wall interval")
                entries.push_back(path + " =" +
                                  entry.substr(entry.find('=') + 1));
            }
        }
      return entries;
    }

    /**
     * Whether two entries "Path = value" of fixed_entries() name the same
     * entry with the same value: the same text, or the same numbers where
     * the texts differ (0.01 and 0.0100, "0,0,1" and "0, 0, 1"), word for
     * word between the separators of lists.
     */
    bool
    same_entry(const std::string &a, const std::string &b)
    {
      if (a == b)
        return true;
      const auto words = [](const std::string &entry) {
        const auto               equals = entry.find(" =");
        std::vector<std::string> result = {entry.substr(0, equals)};
        std::string              word;
        for (const char c : entry.substr(equals + 2) + " ")
          if (c == ',' || c == ';' || c == ':' || c == ' ' || c == '\t')
            {
              if (!word.empty())
                result.push_back(word);
              word.clear();
            }
          else
            word += c;
        return result;
      };
      const std::vector<std::string> x = words(a), y = words(b);
      if (x.size() != y.size() || x[0] != y[0])
        return false;
      for (std::size_t i = 1; i < x.size(); ++i)
        if (x[i] != y[i])
          {
            char        *x_end, *y_end;
            const double x_value = std::strtod(x[i].c_str(), &x_end),
                         y_value = std::strtod(y[i].c_str(), &y_end);
            if (*x_end != '\0' || *y_end != '\0' || !(x_value == y_value))
              return false;
          }
      return true;
    }

    /** The lines of @p text. */
    std::vector<std::string>
    lines_of(const std::string &text)
    {
      std::vector<std::string> lines;
      std::istringstream       in(text);
      for (std::string line; std::getline(in, line);)
        lines.push_back(line);
      return lines;
    }
  } // namespace



  void
  write_checkpoint(
    const std::string                                 &file,
    const std::string                                 &parameters,
    const std::uint64_t                                initial_state,
    const TimeLoopState                               &loop,
    const TimeIntegrator                              &integrator,
    const std::vector<std::unique_ptr<Postprocessor>> &postprocessors)
  {
    // The entries that fix the trajectory (so that runs that differ only in
    // the others, such as the threads, leave the same bytes).
    std::string fixed;
    for (const std::string &entry : fixed_entries(parameters))
      fixed += entry + "\n";
    StateWriter payload;
    payload.put(fixed);
    payload.put(initial_state);
    {
      StateWriter part;
      loop.save(part);
      payload.put(part.data());
    }
    {
      StateWriter part;
      integrator.save_state(part);
      payload.put(part.data());
    }
    payload.put(static_cast<std::uint64_t>(postprocessors.size()));
    for (const auto &postprocessor : postprocessors)
      {
        StateWriter part;
        postprocessor->save_state(part);
        payload.put(part.data());
      }
    StateWriter header;
    header.put(static_cast<std::uint64_t>(payload.data().size()));
    header.put(checksum_of(payload.data()));

    const std::string temporary = file + ".part";
    try
      {
        write_durably(temporary, magic + header.data() + payload.data());
        if (std::rename(temporary.c_str(), file.c_str()) != 0)
          throw OutputFailed("Renaming <" + temporary + "> to <" + file +
                             "> failed: " + std::strerror(errno) + ".");
      }
    catch (const OutputFailed &)
      {
        // No partial checkpoint stays behind (on a full disk, its space is
        // what the summary needs); the previous one is untouched.
        std::remove(temporary.c_str());
        throw;
      }
    // The rename itself reaches the disk with its directory.
    const std::string directory =
      std::filesystem::path(file).parent_path().string();
    const int fd = ::open(directory.empty() ? "." : directory.c_str(),
                          O_RDONLY | O_DIRECTORY);
    if (fd >= 0)
      {
        ::fsync(fd);
        ::close(fd);
      }
  }



  Checkpoint::Checkpoint(const std::string &file)
    : file(file)
  {
    std::error_code failure;
    if (!std::filesystem::is_regular_file(file, failure))
      throw std::runtime_error("Cannot read the checkpoint <" + file +
                               ">: it is not a file.");
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw std::runtime_error("Cannot read the checkpoint <" + file + ">.");
    const std::string bytes((std::istreambuf_iterator<char>(in)),
                            std::istreambuf_iterator<char>());
    const std::size_t header_size = magic.size() + 2 * sizeof(std::uint64_t);
    const std::size_t marked      = std::min(bytes.size(), magic.size());
    if (bytes.compare(0, marked, magic, 0, marked) != 0)
      throw std::runtime_error("<" + file +
                               "> is not a checkpoint of this version of "
                               "estep (it does not start with its mark).");
    if (bytes.size() < header_size)
      throw std::runtime_error("The checkpoint <" + file +
                               "> is damaged (cut short: " +
                               std::to_string(bytes.size()) + " bytes).");
    const std::string header = bytes.substr(magic.size(), header_size);
    StateReader       header_reader(header);
    const auto        size    = header_reader.get<std::uint64_t>();
    const auto        check   = header_reader.get<std::uint64_t>();
    const std::string payload = bytes.substr(header_size);
    if (payload.size() != size || checksum_of(payload) != check)
      throw std::runtime_error("The checkpoint <" + file +
                               "> is damaged (its checksum does not match).");
    contents_checksum = check;
    try
      {
        StateReader reader(payload);
        parameters             = reader.get_string();
        initial_state_checksum = reader.get<std::uint64_t>();
        loop_state             = reader.get_string();
        integrator_state       = reader.get_string();
        postprocessor_states.resize(reader.get<std::uint64_t>());
        for (std::string &state : postprocessor_states)
          state = reader.get_string();
      }
    catch (const std::exception &error)
      {
        throw std::runtime_error("The checkpoint <" + file +
                                 ">: " + error.what());
      }
  }



  void
  Checkpoint::check_parameters(const std::string &current) const
  {
    const std::vector<std::string> then = lines_of(parameters),
                                   now  = fixed_entries(current);
    for (std::size_t i = 0; i < std::max(then.size(), now.size()); ++i)
      if (i >= then.size() || i >= now.size() || !same_entry(then[i], now[i]))
        {
          const std::string &differing = i < now.size() ? now[i] : then[i];
          throw std::runtime_error(
            "--resume: the checkpoint <" + file +
            "> was written with other parameters (first difference: " +
            differing.substr(0, differing.find(" =")) +
            (i < then.size() ? ", then" + then[i].substr(then[i].find(" =")) :
                               "") +
            "); only the end time, the checkpoint entries, the threads and "
            "the output directory may change.");
        }
  }



  std::uint64_t
  Checkpoint::checksum() const
  {
    return contents_checksum;
  }



  void
  Checkpoint::check_initial_state(const std::uint64_t initial_state) const
  {
    if (initial_state != initial_state_checksum)
      throw std::runtime_error(
        "--resume: the checkpoint <" + file +
        "> was written for another initial state (the same parameters, but "
        "a mesh or surface file, or a library they name, has changed since); "
        "the run cannot continue from it.");
  }



  TimeLoopState
  Checkpoint::restore(TimeIntegrator &integrator) const
  {
    TimeLoopState state;
    try
      {
        StateReader loop(loop_state);
        state.load(loop);
        StateReader reader(integrator_state);
        integrator.load_state(reader);
        if (!loop.at_end() || !reader.at_end())
          throw std::runtime_error("its state does not match this build's "
                                   "integrator.");
      }
    catch (const std::exception &error)
      {
        throw std::runtime_error("The checkpoint <" + file +
                                 ">: " + error.what());
      }
    return state;
  }



  void
  Checkpoint::resume(
    const std::vector<std::unique_ptr<Postprocessor>> &postprocessors,
    const bool only_those_on_every_rank) const
  {
    if (postprocessors.size() != postprocessor_states.size())
      throw std::runtime_error("The checkpoint <" + file +
                               "> has the states of " +
                               std::to_string(postprocessor_states.size()) +
                               " postprocessors, the run " +
                               std::to_string(postprocessors.size()) + ".");
    for (const std::size_t i : start_order(postprocessors))
      {
        if (only_those_on_every_rank &&
            !postprocessors[i]->runs_on_every_rank())
          continue;
        StateReader reader(postprocessor_states[i]);
        postprocessors[i]->resume(reader);
        if (!reader.at_end())
          throw std::runtime_error(
            "The checkpoint <" + file +
            ">: a postprocessor's state does not match this build.");
      }
  }
} // namespace estep
