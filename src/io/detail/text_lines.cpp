#include "hgridlab/io/detail/text_lines.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "hgridlab/base/error.hpp"

namespace hgrid::detail {

Lines::Lines(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") at_ = 3;
}

bool Lines::next(std::string_view& line) {
  if (at_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', at_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(at_, end - at_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  at_ = end + 1;
  ++number_;
  return true;
}

std::string Lines::where() const { return name_ + ":" + std::to_string(number_); }

namespace {
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r'; }
}  // namespace

std::vector<std::string_view> split_ws(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_on(std::string_view line, char sep) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t end = line.find(sep, start);
    out.push_back(trim(line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)));
    if (end == std::string_view::npos) return out;
    start = end + 1;
  }
}

bool blank(std::string_view line) { return trim(line).empty(); }

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool to_number(std::string_view token, double& v) {
  if (token.empty() || token.size() > 400) return false;
  const std::string s(token);  // strtod needs a terminated string
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

double finite_number(std::string_view token, const std::string& field, const Lines& at) {
  double v = 0;
  if (!to_number(token, v) || !std::isfinite(v))
    throw InputError(field, "'" + std::string(token.substr(0, 40)) + "' is not a finite number at " + at.where());
  return v;
}

double positive_number(std::string_view token, const std::string& field, const Lines& at) {
  const double v = finite_number(token, field, at);
  if (!(v > 0)) throw InputError(field, "must be > 0 (got " + std::string(token.substr(0, 40)) + ") at " + at.where());
  return v;
}

std::size_t count_number(std::string_view token, const std::string& field, const Lines& at, std::size_t max) {
  double v = 0;
  if (!to_number(token, v) || !(v >= 0) || v != std::floor(v) || v > static_cast<double>(max))
    throw InputError(field, "'" + std::string(token.substr(0, 40)) + "' is not a count in [0, " + std::to_string(max) +
                                "] at " + at.where());
  return static_cast<std::size_t>(v);
}

std::size_t resolve_frame(std::optional<std::int64_t> frame, std::size_t count, const std::string& name) {
  const auto c = static_cast<std::int64_t>(count);
  const std::int64_t k = frame.value_or(-1);
  if (count == 0 || k >= c || k < -c)
    throw InputError("frame", "must be in [" + std::to_string(-c) + ", " + std::to_string(c - 1) + "]: " + name +
                                  " holds " + std::to_string(count) + " snapshot" + (count == 1 ? "" : "s") +
                                  " (got " + std::to_string(k) + ")");
  return static_cast<std::size_t>(k < 0 ? c + k : k);
}

}  // namespace hgrid::detail
