/// @file
/// @brief Internal to the CSV reader (io/csv_reader.h, read_recording): an IMU table recognised
/// by its column names. Finds the time stamp (one column, or the seconds and nanoseconds of a
/// ROS 2 stamp), the gyro and accelerometer axes present (any subset of x, y, z) and the unit
/// each states in brackets, parentheses or a suffix, or that its dialect implies: EuRoC / TUM-VI
/// (`#timestamp [ns],w_RS_S_x [rad s^-1],…`), Kalibr (`timestamp,omega_x,…,alpha_z`: ns, rad/s,
/// m/s²), `rostopic echo -p` (`%time`, `field.header.stamp` in ns, `field.angular_velocity.x`),
/// ROS 2 bag-to-CSV tools (`header.stamp.sec` + `header.stamp.nanosec`, `angular_velocity.x`;
/// sensor_msgs/Imu fields are rad/s and m/s²), PlotJuggler (`__time` in s,
/// `/imu/angular_velocity/x`), imunoise's own names (`gyro_x_rad_per_s`) and plain names
/// (`time,gyro_z`, `acc_x [g]`, `GyroX (deg/s)`). docs/csv-dialects.md lists the rules.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/input_config.h"
#include "io/table_layout.h"

namespace imunoise::io::csv_detail {

/// The time stamp the names point to.
struct HeaderTime {
  std::size_t column = 0;  ///< the stamp, or the seconds of a seconds + nanoseconds pair
  std::optional<std::size_t> nanoseconds_column;  ///< the pair's nanoseconds (ROS 2)
  std::optional<TimeUnit> unit;                   ///< stated or implied; nullopt: not stated
};

/// The axes of one sensor the names point to.
template <typename Unit>
struct HeaderGroup {
  std::vector<std::size_t> columns;  ///< file columns, in axis order
  std::vector<std::size_t> axes;     ///< the axis of each (0 = x, 1 = y, 2 = z)
  std::optional<Unit> unit;          ///< stated or implied; nullopt: not stated
};

/// What the names of a table say.
struct HeaderMapping {
  /// "EuRoC/TUM-VI", "Kalibr", "rostopic echo -p", "ROS 2 stamp", "ROS message fields",
  /// "PlotJuggler", "imunoise" or "named columns"; empty when nothing was recognised.
  std::string dialect;
  std::optional<HeaderTime> time;
  std::optional<HeaderGroup<GyroUnit>> gyro;
  std::optional<HeaderGroup<AccelUnit>> accel;
  /// Why the names give no time, gyro or accel mapping although they name such columns: the
  /// whole "PATH:LINE: …" message (at the header line, naming the columns), for the caller to
  /// throw when it needs that mapping (not when the flags map it).
  std::string time_problem, gyro_problem, accel_problem;
};

/// The mapping LAYOUT's header names give (all empty without a header). A problem (see
/// HeaderMapping) is: one axis of a sensor in two columns (two IMUs, or two spellings), axes of
/// a sensor stating different units, a stated unit that is not one of its sensor's, two time
/// columns equally likely.
HeaderMapping map_imu_header(const TableLayout& layout);

}  // namespace imunoise::io::csv_detail
