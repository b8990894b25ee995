/// @file
/// @brief imunoise.imu_sample_t messages as the samples of pipeline/live_window: decoded from
/// the bytes of a subscription, reduced to the fields a reader uses, and the names those
/// fields carry into a Recording's source columns (the names io::append_imu_sample gives).
#pragma once

#include <cstddef>
#include <imunoise/imu_sample_t.hpp>
#include <optional>

#include "pipeline/live_window.h"

namespace imunoise::io {

/// The fields of M a reader uses: rates, or increments when has_increments; the temperature
/// when has_temperature.
pipeline::ImuSample imu_sample_of(const imunoise::imu_sample_t& m);

/// The imu_sample_t in the SIZE bytes at DATA, or nullopt when they are not exactly one
/// (another type on the channel — decode checks the fingerprint first —, truncated, corrupt).
std::optional<pipeline::ImuSample> decode_imu_sample(const void* data, std::size_t size);

/// The source field and unit of each column for rates and for increments, and the
/// temperature's field, exactly as io::append_imu_sample names them.
pipeline::ImuSampleFields imu_sample_fields();

}  // namespace imunoise::io
