#ifndef estep_base_json_writer_h
#define estep_base_json_writer_h

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace estep
{
  /**
   * A small JSON object builder for summary.json: keys keep their insertion
   * order, values are numbers, strings, booleans, arrays of numbers or of
   * strings, or nested objects.
   */
  class JsonObject
  {
  public:
    JsonObject &
    add(const std::string &key, const double value);
    JsonObject &
    add(const std::string &key, const std::uint64_t value);
    JsonObject &
    add(const std::string &key, const int value);
    JsonObject &
    add(const std::string &key, const unsigned int value);
    JsonObject &
    add(const std::string &key, const std::string &value);
    JsonObject &
    add(const std::string &key, const char *value);
    JsonObject &
    add(const std::string &key, const bool value);
    JsonObject &
    add(const std::string &key, const std::vector<double> &values);
    JsonObject &
    add(const std::string &key, const std::vector<std::string> &values);
    JsonObject &
    add(const std::string &key, const JsonObject &object);

    /** The object as JSON text, indented by @p indent spaces per level. */
    std::string
    to_string(const unsigned int indent = 2,
              const unsigned int level  = 0) const;

  private:
    std::vector<std::pair<std::string, std::string>> members;
  };

  /**
   * Write @p text to @p path atomically: to a temporary file beside it first,
   * then renamed, so that a reader never sees a half-written file. Throws
   * std::runtime_error on failure, after removing the temporary file.
   */
  void
  write_file_atomically(const std::string &path, const std::string &text);
} // namespace estep

#endif
