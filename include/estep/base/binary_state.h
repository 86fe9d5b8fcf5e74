#ifndef estep_base_binary_state_h
#define estep_base_binary_state_h

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace estep
{
  /**
   * The state of a run's parts as bytes, for checkpoints: numbers are stored
   * bit for bit (a double read back is the double written), vectors with
   * their length. Each part writes its state with put() and reads it back,
   * in the same order, with a StateReader.
   */
  class StateWriter
  {
  public:
    /** Store a number (a double, an integer, a bool) bit for bit. */
    template <typename Number>
    void
    put(const Number value)
    {
      static_assert(std::is_arithmetic_v<Number>);
      bytes.append(reinterpret_cast<const char *>(&value), sizeof(value));
    }

    void
    put(const std::string &text);

    /** Store a vector of doubles with its length (any type with size() and
     * operator[]: std::vector<double>, dealii::Vector<double>). */
    template <typename VectorType>
    void
    put_vector(const VectorType &vector)
    {
      put(static_cast<std::uint64_t>(vector.size()));
      for (std::size_t i = 0; i < vector.size(); ++i)
        put(static_cast<double>(vector[i]));
    }

    /** What has been stored. */
    const std::string &
    data() const
    {
      return bytes;
    }

  private:
    std::string bytes;
  };



  /**
   * Reads what a StateWriter stored, in the same order. Reading past the end
   * or a vector of an unexpected length throws std::runtime_error.
   */
  class StateReader
  {
  public:
    /** Read from @p bytes, which must outlive the reader. */
    explicit StateReader(const std::string &bytes);

    template <typename Number>
    Number
    get()
    {
      static_assert(std::is_arithmetic_v<Number>);
      Number value;
      std::memcpy(&value, take(sizeof(value)), sizeof(value));
      return value;
    }

    std::string
    get_string();

    /** Read a vector into @p vector, resized (reinit() or resize()) to the
     * stored length. */
    template <typename VectorType>
    void
    get_vector(VectorType &vector)
    {
      const auto n = get<std::uint64_t>();
      if (n != vector.size())
        {
          if constexpr (has_reinit<VectorType>::value)
            vector.reinit(n);
          else
            vector.resize(n);
        }
      for (std::size_t i = 0; i < n; ++i)
        vector[i] = get<double>();
    }

    /** Whether everything has been read. */
    bool
    at_end() const
    {
      return position == bytes.size();
    }

  private:
    template <typename T, typename = void>
    struct has_reinit : std::false_type
    {};
    template <typename T>
    struct has_reinit<
      T,
      std::void_t<decltype(std::declval<T &>().reinit(std::size_t()))>>
      : std::true_type
    {};

    const char *
    take(const std::size_t n);

    const std::string &bytes;
    std::size_t        position = 0;
  };
} // namespace estep

#endif
