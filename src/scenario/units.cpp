// Units are parsed into a scale factor and powers of the base dimensions (length, mass,
// time, temperature, angle), so compound units ("g/cm^3", "W/(m K)") need no table of
// their own: the parsed powers are compared with those of the expected dimension.
// Angle is kept as a base dimension so that "200 rpm" is an angular velocity and
// "20 /s" is not.
#include "scenario/units.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"

namespace regodem {
namespace {

struct UnitPowers {
  int length = 0, mass = 0, time = 0, temperature = 0, angle = 0;

  constexpr bool operator==(const UnitPowers&) const = default;
  constexpr UnitPowers operator+(const UnitPowers& o) const {
    return {length + o.length, mass + o.mass, time + o.time, temperature + o.temperature,
            angle + o.angle};
  }
  constexpr UnitPowers operator*(int exponent) const {
    return {length * exponent, mass * exponent, time * exponent, temperature * exponent,
            angle * exponent};
  }
};

/// A unit as "factor times SI base units raised to powers".
struct ScaledUnit {
  double factor = 1.0;
  UnitPowers powers;

  ScaledUnit times(const ScaledUnit& o) const { return {factor * o.factor, powers + o.powers}; }
  ScaledUnit power(int exponent) const {
    return {std::pow(factor, exponent), powers * exponent};
  }
};

constexpr UnitPowers kLength{1, 0, 0, 0, 0};
constexpr UnitPowers kMass{0, 1, 0, 0, 0};
constexpr UnitPowers kTime{0, 0, 1, 0, 0};
constexpr UnitPowers kTemperature{0, 0, 0, 1, 0};
constexpr UnitPowers kAngle{0, 0, 0, 0, 1};
constexpr UnitPowers kPerTime{0, 0, -1, 0, 0};
constexpr UnitPowers kForce{1, 1, -2, 0, 0};
constexpr UnitPowers kPressure{-1, 1, -2, 0, 0};
constexpr UnitPowers kEnergy{2, 1, -2, 0, 0};
constexpr UnitPowers kPower{2, 1, -3, 0, 0};

struct NamedUnit {
  std::string_view symbol;
  double factor;
  UnitPowers powers;
  bool takes_prefix;
};

constexpr double kPi = std::numbers::pi;

constexpr std::array kNamedUnits{
    NamedUnit{"m", 1.0, kLength, true},
    NamedUnit{"g", 1e-3, kMass, true},
    NamedUnit{"s", 1.0, kTime, true},
    NamedUnit{"K", 1.0, kTemperature, true},
    NamedUnit{"rad", 1.0, kAngle, true},
    NamedUnit{"Hz", 1.0, kPerTime, true},
    NamedUnit{"N", 1.0, kForce, true},
    NamedUnit{"Pa", 1.0, kPressure, true},
    NamedUnit{"J", 1.0, kEnergy, true},
    NamedUnit{"W", 1.0, kPower, true},
    NamedUnit{"min", 60.0, kTime, false},
    NamedUnit{"h", 3600.0, kTime, false},
    NamedUnit{"deg", kPi / 180.0, kAngle, false},
    NamedUnit{"\u00b0", kPi / 180.0, kAngle, false},  // °
    NamedUnit{"rev", 2.0 * kPi, kAngle, false},
    NamedUnit{"rpm", 2.0 * kPi / 60.0, UnitPowers{0, 0, -1, 0, 1}, false},
    NamedUnit{"%", 0.01, UnitPowers{}, false},
};

struct Prefix {
  std::string_view symbol;
  double factor;
};

constexpr std::array kPrefixes{
    Prefix{"n", 1e-9}, Prefix{"u", 1e-6},      Prefix{"\u00b5", 1e-6} /* micro sign */,
    Prefix{"\u03bc", 1e-6} /* Greek mu */,     Prefix{"m", 1e-3},
    Prefix{"c", 1e-2}, Prefix{"k", 1e3},       Prefix{"M", 1e6},
    Prefix{"G", 1e9},
};

/// Offset temperature scales: only meaningful for a whole quantity, never inside a
/// compound unit (a temperature difference per degC is a kelvin).
struct OffsetTemperatureUnit {
  std::string_view symbol;
  double scale;   // kelvin per degree
  double offset;  // kelvin at zero degrees
};

constexpr std::array kOffsetTemperatureUnits{
    OffsetTemperatureUnit{"degC", 1.0, 273.15},
    OffsetTemperatureUnit{"\u00b0C", 1.0, 273.15},
    OffsetTemperatureUnit{"degF", 5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0},
    OffsetTemperatureUnit{"\u00b0F", 5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0},
};

struct DimensionInfo {
  Dimension dimension;
  UnitPowers powers;
  std::string_view description;
  std::string_view example;
};

// Order matters where two dimensions share powers: the first one names them.
constexpr std::array kDimensions{
    DimensionInfo{Dimension::dimensionless, UnitPowers{}, "a plain number", "0.5"},
    DimensionInfo{Dimension::length, kLength, "a length", "0.6 mm"},
    DimensionInfo{Dimension::area, UnitPowers{2, 0, 0, 0, 0}, "an area", "2 mm^2"},
    DimensionInfo{Dimension::volume, UnitPowers{3, 0, 0, 0, 0}, "a volume", "5 cm^3"},
    DimensionInfo{Dimension::time, kTime, "a time", "0.2 s"},
    DimensionInfo{Dimension::mass, kMass, "a mass", "2 g"},
    DimensionInfo{Dimension::velocity, UnitPowers{1, 0, -1, 0, 0}, "a velocity", "0.5 mm/s"},
    DimensionInfo{Dimension::acceleration, UnitPowers{1, 0, -2, 0, 0}, "an acceleration",
                  "9.81 m/s^2"},
    DimensionInfo{Dimension::angle, kAngle, "an angle", "30 deg"},
    DimensionInfo{Dimension::angular_velocity, UnitPowers{0, 0, -1, 0, 1},
                  "an angular velocity", "200 rpm"},
    DimensionInfo{Dimension::rate, kPerTime, "a rate", "2000 /s"},
    DimensionInfo{Dimension::pressure, kPressure, "a pressure or modulus", "3 GPa"},
    DimensionInfo{Dimension::density, UnitPowers{-3, 1, 0, 0, 0}, "a density", "3000 kg/m^3"},
    DimensionInfo{Dimension::temperature, kTemperature, "a temperature", "-196 degC"},
    DimensionInfo{Dimension::energy, kEnergy, "an energy", "1e-12 J"},
    DimensionInfo{Dimension::force, kForce, "a force", "2 N"},
    DimensionInfo{Dimension::power, kPower, "a power", "5 W"},
    DimensionInfo{Dimension::thermal_conductivity, UnitPowers{1, 1, -3, -1, 0},
                  "a thermal conductivity", "14.76 W/(m K)"},
    DimensionInfo{Dimension::specific_heat, UnitPowers{2, 0, -2, -1, 0}, "a specific heat",
                  "800 J/(kg K)"},
    DimensionInfo{Dimension::heat_transfer_coefficient, UnitPowers{0, 1, -3, -1, 0},
                  "a heat transfer coefficient", "5e4 W/(m^2 K)"},
    DimensionInfo{Dimension::areal_density, UnitPowers{-2, 1, 0, 0, 0}, "an areal density",
                  "7.8 kg/m^2"},
    DimensionInfo{Dimension::temperature_gradient, UnitPowers{-1, 0, 0, 1, 0},
                  "a temperature gradient", "-50 K/m"},
    DimensionInfo{Dimension::stiffness_per_area, UnitPowers{-2, 1, -2, 0, 0},
                  "a stiffness per unit area", "3e10 N/m^3"},
};

const DimensionInfo& info_of(Dimension dimension) {
  for (const DimensionInfo& info : kDimensions) {
    if (info.dimension == dimension) return info;
  }
  throw std::logic_error("units: dimension missing from kDimensions");
}

/// "a mass", or the SI base form ("m^-1 kg^2") when no named dimension matches.
std::string describe_powers(const UnitPowers& powers) {
  for (const DimensionInfo& info : kDimensions) {
    if (info.powers == powers) return std::string(info.description);
  }
  std::string text;
  const std::array<std::pair<std::string_view, int>, 5> parts{{{"m", powers.length},
                                                               {"kg", powers.mass},
                                                               {"s", powers.time},
                                                               {"K", powers.temperature},
                                                               {"rad", powers.angle}}};
  for (const auto& [symbol, exponent] : parts) {
    if (exponent == 0) continue;
    if (!text.empty()) text += ' ';
    text += exponent == 1 ? std::string(symbol) : fmt::format("{}^{}", symbol, exponent);
  }
  return "a quantity in " + text;
}

std::string_view trim(std::string_view text) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

/// A problem in the unit part; parse_quantity adds the whole text to the message.
struct UnitSyntaxError {
  std::string message;
};

/// Recursive descent over a unit expression:
///   expression := ['/'] term { ('*' | '·' | '/' | whitespace) term }
///   term       := factor [ '^' integer | '**' integer | '²' | '³' ]
///   factor     := symbol | '1' | '(' expression ')'
class UnitExpressionParser {
 public:
  explicit UnitExpressionParser(std::string_view text) : text_(text) {}

  ScaledUnit parse() {
    ScaledUnit unit = parse_expression();
    skip_spaces();
    if (pos_ != text_.size()) {
      throw UnitSyntaxError{fmt::format("unexpected '{}' in unit", text_.substr(pos_))};
    }
    return unit;
  }

 private:
  ScaledUnit parse_expression() {
    skip_spaces();
    ScaledUnit result;
    bool divide = false;
    if (consume("/")) {
      divide = true;  // "/s": one per second
    } else {
      result = parse_term();
    }
    for (;;) {
      if (divide) {
        result = result.times(parse_term().power(-1));
        divide = false;
      }
      const std::size_t before_spaces = pos_;
      skip_spaces();
      if (consume("/")) {
        divide = true;
      } else if (consume("*") || consume("\u00b7")) {
        result = result.times(parse_term());
      } else if (pos_ > before_spaces && starts_factor()) {
        result = result.times(parse_term());  // "N m": a space multiplies
      } else {
        pos_ = before_spaces;
        return result;
      }
    }
  }

  ScaledUnit parse_term() {
    ScaledUnit factor = parse_factor();
    const std::size_t before_spaces = pos_;
    skip_spaces();
    if (consume("^") || consume("**")) return factor.power(parse_integer());
    pos_ = before_spaces;  // the spaces may instead separate the next factor
    if (consume("\u00b2")) return factor.power(2);
    if (consume("\u00b3")) return factor.power(3);
    return factor;
  }

  ScaledUnit parse_factor() {
    skip_spaces();
    if (consume("(")) {
      ScaledUnit inner = parse_expression();
      skip_spaces();
      if (!consume(")")) throw UnitSyntaxError{"missing ')' in unit"};
      return inner;
    }
    if (consume("1")) return ScaledUnit{};
    const std::string_view symbol = read_symbol();
    if (symbol.empty()) {
      throw UnitSyntaxError{pos_ < text_.size()
                                ? fmt::format("unexpected '{}' in unit", text_.substr(pos_))
                                : std::string("unit ends too early")};
    }
    return lookup(symbol);
  }

  int parse_integer() {
    skip_spaces();
    const bool negative = consume("-");
    if (!negative) consume("+");
    int value = 0;
    const char* begin = text_.data() + pos_;
    const auto [end, error] = std::from_chars(begin, text_.data() + text_.size(), value);
    if (error != std::errc{}) throw UnitSyntaxError{"expected an integer exponent after '^'"};
    pos_ += static_cast<std::size_t>(end - begin);
    return negative ? -value : value;
  }

  static ScaledUnit lookup(std::string_view symbol) {
    for (const OffsetTemperatureUnit& offset_unit : kOffsetTemperatureUnits) {
      if (symbol == offset_unit.symbol) {
        throw UnitSyntaxError{fmt::format(
            "'{}' can only stand alone, for a temperature; use K inside compound units",
            symbol)};
      }
    }
    for (const NamedUnit& unit : kNamedUnits) {
      if (symbol == unit.symbol) return {unit.factor, unit.powers};
    }
    for (const Prefix& prefix : kPrefixes) {
      if (!symbol.starts_with(prefix.symbol)) continue;
      const std::string_view rest = symbol.substr(prefix.symbol.size());
      for (const NamedUnit& unit : kNamedUnits) {
        if (unit.takes_prefix && rest == unit.symbol) {
          return {prefix.factor * unit.factor, unit.powers};
        }
      }
    }
    throw UnitSyntaxError{fmt::format("unknown unit '{}'", symbol)};
  }

  // Symbols are ASCII letters, '%', and the UTF-8 signs for degree and micro.
  std::size_t symbol_char_length(std::size_t at) const {
    if (at >= text_.size()) return 0;
    const char c = text_[at];
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '%') return 1;
    for (const std::string_view sign : {"\u00b0", "\u00b5", "\u03bc"}) {
      if (text_.substr(at).starts_with(sign)) return sign.size();
    }
    return 0;
  }

  std::string_view read_symbol() {
    const std::size_t start = pos_;
    while (const std::size_t length = symbol_char_length(pos_)) pos_ += length;
    return text_.substr(start, pos_ - start);
  }

  bool starts_factor() const {
    return symbol_char_length(pos_) > 0 ||
           (pos_ < text_.size() && (text_[pos_] == '(' || text_[pos_] == '1'));
  }

  bool consume(std::string_view token) {
    if (!text_.substr(pos_).starts_with(token)) return false;
    pos_ += token.size();
    return true;
  }

  void skip_spaces() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

/// Reads the leading number; returns it and the rest of the text.
std::optional<std::pair<double, std::string_view>> split_number(std::string_view text) {
  std::string_view digits = text;
  if (digits.starts_with('+')) digits.remove_prefix(1);  // from_chars takes no '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc{}) return std::nullopt;
  return std::pair{value, digits.substr(static_cast<std::size_t>(end - digits.data()))};
}

std::string expectation(Dimension expected) {
  const DimensionInfo& info = info_of(expected);
  return fmt::format("expected {} (e.g. {})", info.description, info.example);
}

double checked_temperature(double kelvin, std::string_view text) {
  if (kelvin < 0.0) {
    throw InputError(fmt::format("'{}' is below absolute zero (0 K)", text));
  }
  return kelvin;
}

}  // namespace

std::string dimension_description(Dimension dimension) {
  return std::string(info_of(dimension).description);
}

std::string_view dimension_example(Dimension dimension) { return info_of(dimension).example; }

double parse_quantity(const std::string& text, Dimension expected) {
  const std::string_view trimmed = trim(text);
  const auto number = split_number(trimmed);
  if (!number) {
    throw InputError(fmt::format("{}, got '{}', which is not a number", expectation(expected),
                                 trimmed));
  }
  const double value = number->first;
  if (!std::isfinite(value)) {
    throw InputError(fmt::format("{}, got '{}', which is not a finite number",
                                 expectation(expected), trimmed));
  }
  const std::string_view unit_text = trim(number->second);
  if (unit_text.empty()) {
    return expected == Dimension::temperature ? checked_temperature(value, trimmed) : value;
  }

  for (const OffsetTemperatureUnit& offset_unit : kOffsetTemperatureUnits) {
    if (unit_text != offset_unit.symbol) continue;
    if (expected != Dimension::temperature) {
      throw InputError(fmt::format("{}, got '{}', which is a temperature",
                                   expectation(expected), trimmed));
    }
    return checked_temperature(value * offset_unit.scale + offset_unit.offset, trimmed);
  }

  ScaledUnit unit;
  try {
    unit = UnitExpressionParser(unit_text).parse();
  } catch (const UnitSyntaxError& error) {
    throw InputError(fmt::format("{}, got '{}': {}", expectation(expected), trimmed,
                                 error.message));
  }
  if (!(unit.powers == info_of(expected).powers)) {
    throw InputError(fmt::format("{}, got '{}', which is {}", expectation(expected), trimmed,
                                 describe_powers(unit.powers)));
  }
  const double si_value = value * unit.factor;
  return expected == Dimension::temperature ? checked_temperature(si_value, trimmed) : si_value;
}

}  // namespace regodem
