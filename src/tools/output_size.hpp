#pragma once
// The size of bearing_tool's output files, estimated before a run starts (output_space.hpp
// checks it against the free space). Text files are estimated at the widest their number
// formats print, so the file is not larger (docs/bearing_tool.md "Before a dynamic run").
#include <string>
#include <vector>

#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/dataset_sink.hpp"
#include "bearing_sim/runtime/scenario_simulation.hpp"

namespace bearing_sim::tool {

// Widest of a number printed by "%.10e" with its comma: "-1.2345678901e-05," (an exponent of
// three digits, below 1e-99, adds one character), and by "%.12g" for a time >= 0:
// "0.000123456789012" or "1.23456789012e-05".
constexpr int kScientificCsvFieldBytes = 18;
constexpr int kTimeCsvFieldBytes = 17;

// A CSV of `rows` lines "time,v1,...,vN" (simulate's --csv and --sensor-csv: time "%.12g",
// `values` numbers "%.10e") after a header of `header_bytes`.
double time_series_csv_bytes(double rows, int values, double header_bytes);

// An NPY file of float32 `rows` x `columns`: exact.
double npy_float_bytes(double rows, int columns);

// A channel of generate's CSV: header and `rows` lines "sample,time_s,x,y,z" (sample "%llu",
// time "%.9f" up to `last_time_s`, x y z float32 by "%.9g", at most 15 characters each).
double dataset_csv_bytes(double rows, double last_time_s);

// generate's JSON sidecar (dataset info and the label time line), allowing for every
// defect event of `scenario` in every label.
double dataset_sidecar_bytes(const runtime::DatasetInfo& info, const Scenario& scenario);

// generate's rosbag: every message as the bag writer fills it (serialized length), each
// periodic one at the rate `settings` gives it, with the bag's records around them. At an
// allowance: a health report's texts, the records a chunk adds (its header, an index per
// connection, its chunk info: a few hundred bytes), the field names of a connection record.
constexpr double kHealthTextBytes = 4096.0;
constexpr double kBagChunkAllowanceBytes = 4096.0;
constexpr double kBagConnectionAllowanceBytes = 256.0;
double dataset_bag_bytes(const runtime::DatasetInfo& info, const runtime::GenerateSettings& settings,
                         const Scenario& scenario, int balls);

// All files of one scenario in `formats` (bag, npy, csv), as generate writes them.
double dataset_output_bytes(const runtime::DatasetInfo& info, const runtime::GenerateSettings& settings,
                            const Scenario& scenario, int balls, const std::vector<std::string>& formats);

}  // namespace bearing_sim::tool
