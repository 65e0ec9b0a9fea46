#pragma once
// Reading of the bearing file's `flexible_ring:` block (internal to the core library).
#include "bearing_sim/core/bearing_config.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim::detail {

// Fills c->flexible_ring from the block read by `r` (prefix "flexible_ring."); the rest of
// *c (envelope, material, rotating ring) must already be read. Throws ConfigError naming the key.
void read_flexible_ring(const Reader& r, BearingConfig* c);

}  // namespace bearing_sim::detail
