#include "openscenario/date_time.hpp"

#include <cctype>
#include <string>

namespace orch::openscenario {
namespace {

// Days from 1970-01-01 to y-m-d in the proleptic Gregorian calendar (H. Hinnant's algorithm).
long days_from_civil(long y, long m, long d) {
  y -= m <= 2 ? 1 : 0;
  const long era = (y >= 0 ? y : y - 399) / 400;
  const long yoe = y - era * 400;
  const long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

bool leap(long y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}
  // Exactly `count` digits.
  std::optional<long> digits(std::size_t count) {
    if (pos_ + count > text_.size()) return std::nullopt;
    long value = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const char c = text_[pos_ + i];
      if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
      value = value * 10 + (c - '0');
    }
    pos_ += count;
    return value;
  }
  bool take(char c) {
    if (pos_ < text_.size() && text_[pos_] == c) return ++pos_, true;
    return false;
  }
  [[nodiscard]] bool done() const { return pos_ == text_.size(); }
  [[nodiscard]] std::size_t pos() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

}  // namespace

std::optional<double> parse_date_time(std::string_view text) {
  Cursor c(text);
  const bool negative_year = c.take('-');
  const auto year = c.digits(4);
  if (!year || !c.take('-')) return std::nullopt;
  const auto month = c.digits(2);
  if (!month || !c.take('-')) return std::nullopt;
  const auto day = c.digits(2);
  if (!day || !c.take('T')) return std::nullopt;
  const auto hour = c.digits(2);
  if (!hour || !c.take(':')) return std::nullopt;
  const auto minute = c.digits(2);
  if (!minute || !c.take(':')) return std::nullopt;
  const auto second = c.digits(2);
  if (!second) return std::nullopt;
  double fraction = 0;
  if (c.take('.')) {
    double scale = 0.1;
    bool any = false;
    while (const auto d = c.digits(1)) {
      fraction += scale * static_cast<double>(*d);
      scale /= 10;
      any = true;
    }
    if (!any) return std::nullopt;
  }
  long zone = 0;  // seconds east of UTC
  if (!c.take('Z') && !c.done()) {
    const bool east = c.take('+');
    if (!east && !c.take('-')) return std::nullopt;
    const auto zh = c.digits(2);
    if (!zh || !c.take(':')) return std::nullopt;
    const auto zm = c.digits(2);
    if (!zm || *zh > 14 || *zm > 59) return std::nullopt;
    zone = (east ? 1 : -1) * (*zh * 3600 + *zm * 60);
  }
  if (!c.done()) return std::nullopt;
  const long y = negative_year ? -*year : *year;
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (*month < 1 || *month > 12) return std::nullopt;
  const long month_days = kDays[*month - 1] + (*month == 2 && leap(y) ? 1 : 0);
  if (*day < 1 || *day > month_days) return std::nullopt;
  // 24:00:00 is the end of the day (XML Schema); seconds up to 59 (no leap seconds).
  if (*hour > 24 || *minute > 59 || *second > 59 || (*hour == 24 && (*minute || *second || fraction > 0)))
    return std::nullopt;
  const long seconds = days_from_civil(y, *month, *day) * 86400 + *hour * 3600 + *minute * 60 + *second - zone;
  return static_cast<double>(seconds) + fraction;
}

}  // namespace orch::openscenario
