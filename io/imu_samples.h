/// @file
/// @brief io's names for pipeline/imu_samples.h: the columns of IMU samples from messages and
/// their conversion to a Recording moved to pipeline/ (pure computation, shared by the LCM log
/// reader here and the live window there); the readers of io/ keep using them as io::.
#pragma once

#include "pipeline/imu_samples.h"

namespace imunoise::io {

using pipeline::ImuSampleColumns;
using pipeline::recording_from_imu_samples;

}  // namespace imunoise::io
