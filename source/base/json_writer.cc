#include <estep/base/json_writer.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    std::string
    quoted(const std::string &text)
    {
      std::string result = "\"";
      for (const char c : text)
        {
          if (c == '"' || c == '\\')
            result += '\\', result += c;
          else if (c == '\n')
            result += "\\n";
          else if (static_cast<unsigned char>(c) < 0x20)
            result += ' ';
          else
            result += c;
        }
      return result + "\"";
    }

    std::string
    number(const double x)
    {
      if (!std::isfinite(x))
        return "null"; // JSON has no inf or nan
      std::ostringstream out;
      out << std::setprecision(17) << x;
      return out.str();
    }
  } // namespace

  JsonObject &
  JsonObject::add(const std::string &key, const double value)
  {
    members.emplace_back(key, number(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const std::uint64_t value)
  {
    members.emplace_back(key, std::to_string(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const int value)
  {
    members.emplace_back(key, std::to_string(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const unsigned int value)
  {
    members.emplace_back(key, std::to_string(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const std::string &value)
  {
    members.emplace_back(key, quoted(value));
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const char *value)
  {
    return add(key, std::string(value));
  }

  JsonObject &
  JsonObject::add(const std::string &key, const bool value)
  {
    members.emplace_back(key, value ? "true" : "false");
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const std::vector<double> &values)
  {
    std::string text = "[";
    for (unsigned int i = 0; i < values.size(); ++i)
      text += (i ? ", " : "") + number(values[i]);
    members.emplace_back(key, text + "]");
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string              &key,
                  const std::vector<std::string> &values)
  {
    std::string text = "[";
    for (unsigned int i = 0; i < values.size(); ++i)
      text += (i ? ", " : "") + quoted(values[i]);
    members.emplace_back(key, text + "]");
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const JsonObject &object)
  {
    members.emplace_back(key, "\x01" + object.to_string(2, 0));
    return *this;
  }

  std::string
  JsonObject::to_string(const unsigned int indent,
                        const unsigned int level) const
  {
    const std::string pad((level + 1) * indent, ' '),
      end_pad(level * indent, ' ');
    std::string text = "{\n";
    for (unsigned int i = 0; i < members.size(); ++i)
      {
        std::string value = members[i].second;
        if (!value.empty() && value[0] == '\x01')
          {
            // A nested object: indent its lines one level deeper.
            value.erase(0, 1);
            std::string shifted;
            for (const char c : value)
              {
                shifted += c;
                if (c == '\n')
                  shifted += pad;
              }
            value = shifted;
          }
        text += pad + quoted(members[i].first) + ": " + value +
                (i + 1 < members.size() ? ",\n" : "\n");
      }
    return text + end_pad + "}";
  }



  void
  write_file_atomically(const std::string &path, const std::string &text)
  {
    const std::string temporary = path + ".part";
    {
      std::ofstream out(temporary);
      out << text;
      out.close();
      if (!out)
        {
          std::remove(temporary.c_str()); // no partial file stays behind
          throw std::runtime_error("Cannot write the file <" + temporary +
                                   ">.");
        }
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
      {
        std::remove(temporary.c_str());
        throw std::runtime_error("Cannot rename <" + temporary + "> to <" +
                                 path + ">.");
      }
  }
} // namespace estep
