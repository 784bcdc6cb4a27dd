// Per-point acquisition time of a spinning-LiDAR scan, read from whatever convention the driver
// uses, as seconds relative to the scan's header stamp (the pose the odometry estimates).
//
// Drivers differ in the field's name, type, unit and origin:
//   Velodyne   `time`        float32 s   from the header stamp (>= 0, or <= 0 when stamped last)
//   Ouster     `t`           uint32 ns   from the header stamp (the first column)
//   Hesai      `timestamp`   float64 s   absolute (unix time)
//   Robosense  `timestamp`   float64 s   absolute
//   Livox      `offset_time` uint32 ns   from the header stamp
// and converted bags carry `time`/`t` in s, ms, us or ns. The unit is decided from the values
// themselves: absolute times lie near the header stamp in exactly one unit, relative ones span
// about one scan period in exactly one unit (the candidates are 1000x apart).
#pragma once

#include <string>
#include <vector>

namespace tacs {

struct PointTimeConfig {
  // Field holding the per-point time: "auto" tries time, t, timestamp, offset_time, time_stamp in
  // that order; "none" never deskews; any other name is used as given.
  std::string time_field = "auto";
  // Unit of that field: auto | s | ms | us | ns.
  std::string time_unit = "auto";
  // What the field's values count from: auto (absolute values are recognised, otherwise the
  // header stamp) | header (relative to the header stamp) | first_point (relative to the first
  // point, the header stamp marks the first point) | last_point (relative to the first point,
  // the header stamp marks the last point) | absolute.
  std::string time_origin = "auto";
  double scan_period_s = 0.1;  // [s] nominal sweep duration; relative times must span about this

  template <class V>
  void visit(V& v) {
    v("time_field", time_field);
    v("time_unit", time_unit);
    v("time_origin", time_origin);
    v("scan_period_s", scan_period_s);
  }
  void validate() const;
};

/// Field names tried, in order, when time_field is "auto".
const std::vector<std::string>& autoTimeFieldNames();

/// What resolvePointTimes() made of a field.
struct PointTimes {
  bool ok = false;
  // Why there are no usable times (ok == false). `reason` is a short stable key for grouping
  // warnings ("constant", "non_finite", ...), `message` says it for a user.
  std::string reason;
  std::string message;
  std::string unit;       // the unit found or configured: s, ms, us or ns
  bool absolute = false;  // the values were absolute times
  // [s] per point, relative to the header stamp: the point was measured at stamp + offset_s[i].
  std::vector<float> offset_s;
  double span_s = 0.0;  // [s] last minus first measurement time
};

/// Converts the raw values of `field` (one per point, in the field's own unit) into offsets from
/// `header_stamp` [s]. Never throws: constant, non-finite, decreasing, wrongly scaled or
/// out-of-range values give ok == false with the reason, and the scan is then used without
/// deskewing.
PointTimes resolvePointTimes(const std::string& field, const std::vector<double>& raw,
                             double header_stamp, const PointTimeConfig& config);

}  // namespace tacs
