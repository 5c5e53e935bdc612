// SPDX-License-Identifier: BSD-3-Clause
/// @file number_parsing.h
/// Whole-token number parsing at std::from_chars speed, for the text readers (OFF, OBJ).
#pragma once

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <system_error>

namespace tc
{
namespace detail
{
/// How from_chars read a whole token.
enum class Parsed
{
  Ok,
  OutOfRange, ///< every character read, but the value is beyond the type's range
  Bad,
};

/// std::from_chars over the whole token, after an optional leading '+' (which from_chars does
/// not take).
template <typename T>
Parsed parseWhole(std::string_view token, T& value)
{
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+')
  {
    ++begin;
  }
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ptr != end || begin == end)
  {
    return Parsed::Bad;
  }
  return ec == std::errc()
    ? Parsed::Ok
    : (ec == std::errc::result_out_of_range ? Parsed::OutOfRange : Parsed::Bad);
}

/// A whole token as a double. Values beyond the double range become +-Inf or 0 as strtod makes
/// them.
inline bool parseDouble(std::string_view token, double& value)
{
  const Parsed parsed = parseWhole(token, value);
  if (parsed == Parsed::OutOfRange)
  {
    value = std::strtod(std::string(token).c_str(), nullptr);
  }
  return parsed != Parsed::Bad;
}

/// A whole token as an int64; false for anything else, an out-of-range value included.
inline bool parseInteger(std::string_view token, int64_t& value)
{
  return parseWhole(token, value) == Parsed::Ok;
}
} // namespace detail
} // namespace tc
