#include "tacs_graphs/odometry/point_times.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

#include "tacs_graphs/common/config.h"

namespace tacs {

namespace {

struct Unit {
  const char* name;
  double seconds;
};
constexpr std::array<Unit, 4> kUnits = {{{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}, {"ns", 1e-9}}};

const Unit* findUnit(const std::string& name) {
  for (const Unit& u : kUnits) {
    if (name == u.name) return &u;
  }
  return nullptr;
}

// Relative times span about one sweep: accept 1/20 (a cropped cloud) to 5 sweeps. The window is
// 100x wide, narrower than the 1000x between units, so at most one unit fits.
constexpr double kMinSpanPeriods = 0.05;
constexpr double kMaxSpanPeriods = 5.0;

std::string formatDouble(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), fmt, value);
  return buffer;
}

PointTimes fail(std::string reason, std::string message) {
  PointTimes out;
  out.reason = std::move(reason);
  out.message = std::move(message);
  return out;
}

struct Range {
  double min = 0.0, max = 0.0;
  double span() const { return max - min; }
};

// A relative field: its values stay within a few sweeps of zero and span about one sweep.
bool fitsRelative(const Range& r, double unit_s, double period_s) {
  const double span = r.span() * unit_s;
  const double reach = std::max(std::abs(r.min), std::abs(r.max)) * unit_s;
  return span >= kMinSpanPeriods * period_s && span <= kMaxSpanPeriods * period_s &&
         reach <= kMaxSpanPeriods * period_s;
}

// An absolute field: its values lie near the header stamp.
bool fitsAbsolute(const Range& r, double unit_s, double stamp, double period_s) {
  const double tolerance = std::max(1.0, 10.0 * period_s);
  return std::abs(r.min * unit_s - stamp) <= tolerance &&
         std::abs(r.max * unit_s - stamp) <= tolerance;
}

// Mean of the first and of the last 5 % of the values in point order: a field whose end lies
// before its start runs backwards (drivers store a sweep in time order, row by row or by column).
bool runsBackwards(const std::vector<double>& raw, const Range& r) {
  const size_t n = std::max<size_t>(1, raw.size() / 20);
  double head = 0.0, tail = 0.0;
  for (size_t i = 0; i < n; ++i) {
    head += raw[i];
    tail += raw[raw.size() - 1 - i];
  }
  return (head - tail) / n > 0.5 * r.span();
}

}  // namespace

void PointTimeConfig::validate() const {
  requireConfig(!time_field.empty(), "odometry.point_times.time_field",
                "must be auto, none or a field name");
  requireConfig(time_unit == "auto" || findUnit(time_unit), "odometry.point_times.time_unit",
                "must be one of auto, s, ms, us, ns (got '" + time_unit + "')");
  static const std::array<const char*, 5> kOrigins = {"auto", "header", "first_point", "last_point",
                                                      "absolute"};
  requireConfig(
      std::find(kOrigins.begin(), kOrigins.end(), time_origin) != kOrigins.end(),
      "odometry.point_times.time_origin",
      "must be one of auto, header, first_point, last_point, absolute (got '" + time_origin + "')");
  requireConfig(scan_period_s > 0.0, "odometry.point_times.scan_period_s", "must be > 0");
}

const std::vector<std::string>& autoTimeFieldNames() {
  static const std::vector<std::string> names = {"time", "t", "timestamp", "offset_time",
                                                 "time_stamp"};
  return names;
}

PointTimes resolvePointTimes(const std::string& field, const std::vector<double>& raw,
                             double header_stamp, const PointTimeConfig& config) {
  const std::string quoted = "time field '" + field + "'";
  if (raw.empty()) return fail("empty", quoted + " has no values");
  Range r{raw.front(), raw.front()};
  for (double v : raw) {
    if (!std::isfinite(v)) return fail("non_finite", quoted + " holds NaN or infinite values");
    r.min = std::min(r.min, v);
    r.max = std::max(r.max, v);
  }
  if (r.span() <= 0.0) return fail("constant", quoted + " is constant");
  if (runsBackwards(raw, r)) return fail("decreasing", quoted + " decreases along the scan");

  const double period = config.scan_period_s;
  const Unit* unit = findUnit(config.time_unit);
  std::string origin = config.time_origin;
  if (origin == "auto") {  // relative if it spans a sweep near zero, else absolute if near stamp
    for (const Unit& u : kUnits) {
      if ((!unit || unit == &u) && fitsRelative(r, u.seconds, period)) {
        unit = &u, origin = "header";
        break;
      }
    }
    for (const Unit& u : kUnits) {
      if (origin == "auto" && (!unit || unit == &u) &&
          fitsAbsolute(r, u.seconds, header_stamp, period)) {
        unit = &u, origin = "absolute";
      }
    }
    if (origin == "auto") {
      return fail("unit",
                  quoted + " spans " + formatDouble("%g", r.span()) + " (values " +
                      formatDouble("%g", r.min) + " to " + formatDouble("%g", r.max) +
                      "): in no unit (s, ms, us, ns) one sweep of about " +
                      formatDouble("%g", period) +
                      " s near zero or near the header stamp; set odometry.point_times.time_unit "
                      "and time_origin");
    }
  } else if (!unit) {  // origin given, unit from the span
    for (const Unit& u : kUnits) {
      const double span = r.span() * u.seconds;
      if (span >= kMinSpanPeriods * period && span <= kMaxSpanPeriods * period) unit = &u;
    }
    if (!unit) {
      return fail("unit", quoted + " spans " + formatDouble("%g", r.span()) +
                              ", about one sweep of " + formatDouble("%g", period) +
                              " s in no unit; set odometry.point_times.time_unit");
    }
  }

  PointTimes out;
  out.unit = unit->name;
  out.absolute = origin == "absolute";
  double shift = 0.0;  // offset = value * unit - shift
  if (origin == "absolute") shift = header_stamp;
  if (origin == "first_point") shift = r.min * unit->seconds;
  if (origin == "last_point") shift = r.max * unit->seconds;
  out.span_s = r.span() * unit->seconds;
  if (out.span_s > kMaxSpanPeriods * period) {
    return fail("unit", quoted + " spans " + formatDouble("%g", out.span_s) + " s in " +
                            unit->name + ", more than " + formatDouble("%g", kMaxSpanPeriods) +
                            " sweeps of " + formatDouble("%g", period) + " s");
  }
  const double first = r.min * unit->seconds - shift, last = r.max * unit->seconds - shift;
  if (std::max(std::abs(first), std::abs(last)) > kMaxSpanPeriods * period) {
    return fail("offset",
                quoted + " puts points " +
                    formatDouble("%.3f", std::abs(first) > std::abs(last) ? first : last) +
                    " s from the header stamp (" + unit->name + ", origin " + origin + ")");
  }
  out.offset_s.resize(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    out.offset_s[i] = static_cast<float>(raw[i] * unit->seconds - shift);
  }
  out.ok = true;
  return out;
}

}  // namespace tacs
