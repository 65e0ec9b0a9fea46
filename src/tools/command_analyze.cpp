// bearing_tool analyze: condition indicators, envelope analysis and a diagnosis of a
// recorded (or simulated) acceleration signal in a CSV file (docs/health.md).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "commands.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

struct AnalyzeCliOptions {
  std::string csv;
  std::string bearing;
  double outer_rpm = 0.0;
  double inner_rpm = 0.0;
  std::string column = "ax_m_s2";
  double rate_hz = 0.0;
  double window_s = 0.0;
  double resonance_hz = 0.0;
  double band_width_hz = 2000.0;
  std::vector<double> zones{1.4, 2.8, 4.5};
  double snr_db = bearing_sim::DiagnosisThresholds{}.fault_snr_db;
  double kurtosis_warn = bearing_sim::DiagnosisThresholds{}.kurtosis_warn;
  bool json = false;
};

struct CsvSignal {
  std::vector<double> values;
  double rate_hz = 0.0;  // from the time column; 0 when there is none
  std::string column;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return cells;
}

// Other spellings of the accelerometer columns of `bearing_tool simulate --csv`.
std::string canonical_column(const std::string& name) {
  if (name == "accel_x") return "ax_m_s2";
  if (name == "accel_y") return "ay_m_s2";
  if (name == "accel_z") return "az_m_s2";
  return name;
}

double parse_cell(const std::string& text, const std::string& path, std::size_t line, const std::string& column) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw InputError("--csv '" + path + "' line " + std::to_string(line) + ", column '" + column + "': '" + text +
                     "' is not a finite number");
  return v;
}

// A header line of column names, then one sample per line.
// The most a step of the time column may differ from the median step, as a share of it.
// A missing sample makes a step of twice the median (100 % off), so any hole is caught, while
// time stamps written with a microsecond's resolution at 200 kHz (steps of 5 us +- 1 us) pass.
constexpr double kTimeStepTolerance = 0.25;

// A header line of column names, then one sample per line. With `use_time` the first column
// whose name starts with "time" gives the rate and must increase in uniform steps.
CsvSignal read_csv(const std::string& path, const std::string& wanted, bool use_time) {
  // A directory opens but reads as empty; /dev/zero or a FIFO would be read forever.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("--csv '" + path +
                     "': " + (std::filesystem::exists(path, ec) ? "not a regular file" : "no such file"));
  std::ifstream in(path);
  if (!in) throw InputError("--csv: cannot open '" + path + "': " + std::strerror(errno));
  std::string line;
  if (!std::getline(in, line)) throw InputError("--csv '" + path + "': empty file (a header line is expected)");
  const std::vector<std::string> header = split(line);
  // Two columns of one name: which one is meant cannot be known (the last used to win).
  for (std::size_t i = 0; i < header.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (!header[i].empty() && header[i] == header[j])
        throw InputError("--csv '" + path + "' line 1: column '" + header[i] + "' appears twice (columns " +
                         std::to_string(j + 1) + " and " + std::to_string(i + 1) + "); give each column its own name");
  int value_col = -1, time_col = -1;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == wanted) value_col = static_cast<int>(i);
    if (use_time && time_col < 0 && header[i].rfind("time", 0) == 0) time_col = static_cast<int>(i);
  }
  if (value_col < 0) {
    const std::string alias = canonical_column(wanted);
    for (std::size_t i = 0; i < header.size() && value_col < 0; ++i)
      if (header[i] == alias) value_col = static_cast<int>(i);
  }
  if (value_col < 0) {
    std::string names;
    for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
    throw InputError("--column '" + wanted + "': no such column in '" + path + "' (columns: " + names + ")");
  }
  CsvSignal s;
  s.column = header[value_col];
  std::vector<double> time;
  std::vector<std::size_t> time_line;  // the file's line of each time
  std::size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> cells = split(line);
    const int needed = std::max(value_col, time_col) + 1;
    if (static_cast<int>(cells.size()) < needed)
      throw InputError("--csv '" + path + "' line " + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                       " columns, " + std::to_string(needed) + " needed");
    s.values.push_back(parse_cell(cells[value_col], path, line_no, s.column));
    if (time_col >= 0) {
      const double t = parse_cell(cells[time_col], path, line_no, header[time_col]);
      // Samples out of order (or repeated) would give a wrong rate and a garbled spectrum.
      if (!time.empty() && !(t > time.back()))
        throw InputError("--csv '" + path + "' line " + std::to_string(line_no) + ", column '" + header[time_col] +
                         "': time " + general(t, 12) + " does not increase (previous sample " +
                         general(time.back(), 12) + ")");
      time.push_back(t);
      time_line.push_back(line_no);
    }
  }
  if (time.size() >= 2) {
    // A hole (samples missing) or a jump would stretch the rate (n-1)/span and smear every
    // line of the spectrum: the steps must be uniform about their median.
    std::vector<double> steps(time.size() - 1);
    for (std::size_t i = 0; i + 1 < time.size(); ++i) steps[i] = time[i + 1] - time[i];
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t i = 0; i < steps.size(); ++i)
      if (std::abs(steps[i] - median) > kTimeStepTolerance * median)
        throw InputError("--csv '" + path + "' line " + std::to_string(time_line[i + 1]) + ", column '" +
                         header[time_col] + "': time " + general(time[i + 1], 12) + " is " + general(steps[i], 6) +
                         " s after the previous sample (line " + std::to_string(time_line[i]) +
                         "), the median step is " + general(median, 6) + " s (" + general(1.0 / median, 6) +
                         " Hz): the time steps must agree within " + fixed(kTimeStepTolerance * 100.0, 0) +
                         " % (a gap or jump in the record); if the samples are consecutive and only the time "
                         "stamps are off, give --rate (the time column is then not read)");
    s.rate_hz = static_cast<double>(time.size() - 1) / (time.back() - time.front());
  }
  return s;
}

nlohmann::json peak_json(const SpectralPeak& p) {
  return {{"expected_hz", p.expected_hz},      {"searched", p.searched},
          {"frequency_hz", p.frequency_hz},    {"amplitude_m_s2", p.amplitude},
          {"noise_floor_m_s2", p.noise_floor}, {"snr_db", p.snr_db},
          {"local_maximum", p.local_maximum},  {"chance", p.chance}};
}

// "24/13*/-" : the SNR of each line (from `first`), * when found, - when not searched.
std::string evidence_cell(const std::vector<EvidenceLine>& lines, std::size_t first) {
  std::string cell;
  for (std::size_t i = first; i < lines.size(); ++i) {
    const EvidenceLine& l = lines[i];
    cell += (cell.empty() ? "" : "/") + (l.peak.searched ? fixed(l.peak.snr_db, 0) + (l.found ? "*" : "") : "-");
  }
  return cell.empty() ? "-" : cell;
}

nlohmann::json evidence_json(const std::vector<EvidenceLine>& lines) {
  nlohmann::json a = nlohmann::json::array();
  for (const EvidenceLine& l : lines)
    a.push_back({{"order", l.order},
                 {"offset_hz", l.offset_hz},
                 {"found", l.found},
                 {"shared", l.shared},
                 {"peak", peak_json(l.peak)}});
  return a;
}

nlohmann::json verdict_json(const Verdict& v) {
  nlohmann::json kinds = nlohmann::json::array();
  for (FaultKind k : v.kinds) kinds.push_back(fault_kind_name(k));
  return {{"outcome", verdict_outcome_name(v.outcome)}, {"kinds", kinds}, {"text", v.text}};
}

void run(const AnalyzeCliOptions& o) {
  if (!(o.snr_db >= kMinFaultSnrDb && o.snr_db <= kMaxFaultSnrDb))
    throw InputError("--snr-db " + general(o.snr_db, 6) + ": must be from " + general(kMinFaultSnrDb, 3) + " to " +
                     general(kMaxFaultSnrDb, 3) + " dB (a line that many dB over its noise floor is a fault)");
  if (!(o.kurtosis_warn == 0.0 || (o.kurtosis_warn >= kMinKurtosisWarn && o.kurtosis_warn <= kMaxKurtosisWarn)))
    throw InputError("--kurtosis-warn " + general(o.kurtosis_warn, 6) + ": must be 0 (off) or from " +
                     general(kMinKurtosisWarn, 3) + " (Gaussian noise) to " + general(kMaxKurtosisWarn, 4));
  const BearingModel model = load_model(o.bearing);
  if (o.inner_rpm == 0.0 && o.outer_rpm == 0.0)
    throw InputError(
        "give the ring speeds of the recording (--inner-rpm and/or --outer-rpm): the fault "
        "frequencies depend on them");
  // --rate: the samples are consecutive at that rate, whatever a time column says.
  const CsvSignal signal = read_csv(o.csv, o.column, !(o.rate_hz > 0.0));
  const double rate = o.rate_hz > 0.0 ? o.rate_hz : signal.rate_hz;
  if (!(rate > 0.0))
    throw InputError("--csv '" + o.csv + "' has no time column (a header starting with 'time'): give --rate");
  const BearingFrequencies f = bearing_frequencies(model, rpm_to_rad_s(o.inner_rpm), rpm_to_rad_s(o.outer_rpm));

  AnalysisOptions a;
  a.window_s = o.window_s;
  a.resonance_hz = o.resonance_hz;
  a.envelope_band_width_hz = o.band_width_hz;
  a.zones = {o.zones[0], o.zones[1], o.zones[2]};
  if (!(a.zones.ab_mm_s > 0.0 && a.zones.ab_mm_s < a.zones.bc_mm_s && a.zones.bc_mm_s < a.zones.cd_mm_s))
    throw InputError("--zones: expected 0 < A/B < B/C < C/D (mm/s)");
  a.thresholds.fault_snr_db = o.snr_db;
  a.thresholds.kurtosis_warn = o.kurtosis_warn;
  const ConditionIndicators c = analyze_vibration(signal.values, rate, f, a);

  nlohmann::json faults = nlohmann::json::array();
  for (const FaultIndicator& fi : c.faults) {
    faults.push_back({{"fault", fault_kind_name(fi.kind)},
                      {"label", fault_frequency_label(fi.kind)},
                      {"suspected", fi.suspected},
                      {"modulation", fi.modulation},
                      {"envelope_peak", peak_json(fi.envelope_peak)},
                      {"harmonics_found", fi.harmonics_found},
                      {"harmonics", evidence_json(fi.harmonics)},
                      {"sidebands_required", fi.sidebands_required},
                      {"modulation_hz", fi.modulation_hz},
                      {"sidebands_found", fi.sidebands_found},
                      {"sidebands", evidence_json(fi.sidebands)},
                      {"resolvable", fi.resolvable},
                      {"impulsiveness_required", fi.impulsiveness_required},
                      {"impulsive", fi.impulsive},
                      {"note", fi.note}});
    if (fi.intervals.tested)  // rule 14, the ball series
      faults.back()["impact_intervals"] = {{"period_s", fi.intervals.period_s},   {"impacts", fi.intervals.impacts},
                                           {"in_window", fi.intervals.in_window}, {"around", fi.intervals.around},
                                           {"expected", fi.intervals.expected},   {"chance", fi.intervals.chance},
                                           {"median_ratio", fi.intervals.median_ratio},
                                           {"found", fi.intervals.found}};
  }
  const nlohmann::json result = {{"bearing", bearing_json(model, o.bearing)},
                                 {"csv", o.csv},
                                 {"column", signal.column},
                                 {"inner_rpm", o.inner_rpm},
                                 {"outer_rpm", o.outer_rpm},
                                 {"sample_rate_hz", rate},
                                 {"samples", c.samples},
                                 {"window_s", c.window_s},
                                 {"rms_m_s2", c.acceleration.rms},
                                 {"peak_m_s2", c.acceleration.peak},
                                 {"crest_factor", c.acceleration.crest_factor},
                                 {"kurtosis", c.acceleration.kurtosis},
                                 {"L_dB", c.level_db},
                                 {"velocity_rms_mm_s", c.velocity_rms_mm_s},
                                 {"velocity_band_hz", {c.velocity_low_hz, c.velocity_high_hz}},
                                 {"zone", velocity_zone_name(c.zone)},
                                 {"zone_boundaries_mm_s", o.zones},
                                 {"envelope_band_hz", {c.envelope_low_hz, c.envelope_high_hz}},
                                 {"envelope_band_source", c.envelope_band_source},
                                 {"envelope_band_kurtosis", c.envelope_band_kurtosis},
                                 {"envelope_band_independent_samples", c.envelope_band_independent_samples},
                                 {"envelope_mean_m_s2", c.envelope_mean_m_s2},
                                 {"envelope_resolution_hz", c.envelope.resolution_hz},
                                 {"envelope_source", c.envelope_source},
                                 {"speed_measured", c.speed_measured},
                                 {"speed_scale", c.speed_scale},
                                 {"envelope_segments", c.envelope_segments},
                                 {"fault_snr_db_used", c.fault_snr_db_used},
                                 {"faults", faults},
                                 {"level", health_level_name(c.diagnosis.level)},
                                 {"reason", c.diagnosis.reason},
                                 {"verdict", verdict_json(c.diagnosis.verdict)}};
  // L and an SNR are +-inf for a silent signal (written as null).
  require_finite_result(result, "analyze", {"L_dB", "snr_db"});
  if (o.json) {
    print_json(result);
    return;
  }

  std::ostream& out = std::cout;
  out << "Bearing: " << model.config().name << " (" << o.bearing << "), inner ring " << general(o.inner_rpm, 6)
      << " rpm, outer ring " << general(o.outer_rpm, 6) << " rpm\n"
      << "Signal: " << o.csv << ", column " << signal.column << ", " << c.samples << " samples at " << general(rate, 6)
      << " Hz (last " << fixed(c.window_s, 3) << " s)\n\n";
  Table t({"indicator", "value", "unit"}, {true, false, true});
  t.add_row({"RMS", scientific(c.acceleration.rms, 4), "m/s^2"});
  t.add_row({"peak", scientific(c.acceleration.peak, 4), "m/s^2"});
  t.add_row({"crest factor", fixed(c.acceleration.crest_factor, 3), ""});
  t.add_row({"kurtosis (Gaussian 3)", fixed(c.acceleration.kurtosis, 3), ""});
  t.add_row({"L (JB/T 5314, a0 = 9.81e-3 m/s^2)", fixed(c.level_db, 2), "dB"});
  t.add_row({"velocity RMS " + general(c.velocity_low_hz, 4) + "-" + general(c.velocity_high_hz, 4) + " Hz",
             fixed(c.velocity_rms_mm_s, 3), "mm/s"});
  t.add_row({"ISO 20816-3 zone (A/B/C/D at " + general(o.zones[0], 3) + "/" + general(o.zones[1], 3) + "/" +
                 general(o.zones[2], 3) + " mm/s)",
             velocity_zone_name(c.zone), ""});
  t.print(out);
  out << "\nEnvelope spectrum (band " << fixed(c.envelope_low_hz, 0) << "-" << fixed(c.envelope_high_hz, 0)
      << " Hz from the " << c.envelope_band_source << ", spectral kurtosis " << fixed(c.envelope_band_kurtosis, 2)
      << ", resolution " << fixed(c.envelope.resolution_hz, 3) << " Hz; noise = median of the neighbouring bins)\n";
  Table e({"fault", "frequency", "expected Hz", "peak Hz", "amplitude m/s^2", "SNR dB", "harmonics dB", "sidebands dB",
           "suspected"},
          {true, true, false, false, false, false, false, false, true});
  for (const FaultIndicator& fi : c.faults) {
    const SpectralPeak& p = fi.envelope_peak;
    e.add_row({fault_kind_name(fi.kind), fault_frequency_label(fi.kind), fixed(p.expected_hz, 2),
               p.searched ? fixed(p.frequency_hz, 2) : "-", p.searched ? scientific(p.amplitude, 3) : "-",
               p.searched ? fixed(p.snr_db, 1) : "-", evidence_cell(fi.harmonics, 1),
               fi.sidebands_required ? evidence_cell(fi.sidebands, 0) : "n/a", fi.suspected ? "yes" : "no"});
  }
  e.print(out);
  for (const FaultIndicator& fi : c.faults)
    if (!fi.note.empty()) out << fault_frequency_label(fi.kind) << ": " << fi.note << "\n";
  out << "\nDiagnosis: " << health_level_name(c.diagnosis.level) << ": " << c.diagnosis.reason << "\n";
  out << "Verdict: " << c.diagnosis.verdict.text << "\n";
}

}  // namespace

void register_analyze_command(CLI::App& app) {
  auto o = std::make_shared<AnalyzeCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "analyze",
      "Condition indicators of a recorded acceleration signal (CSV): RMS, peak, crest factor, kurtosis, L, "
      "velocity RMS and ISO 20816-3 zone, envelope spectrum at the fault frequencies, diagnosis");
  cmd->add_option("--csv", o->csv, "CSV file with a header line (e.g. from 'bearing_tool simulate --csv')")
      ->required()
      ->type_name("FILE");
  add_bearing_option(cmd, &o->bearing);
  add_number_option(cmd, "--outer-rpm", &o->outer_rpm, "RPM", "Outer ring speed during the recording, rpm (signed)");
  add_number_option(cmd, "--inner-rpm", &o->inner_rpm, "RPM", "Inner ring speed during the recording, rpm (signed)");
  cmd->add_option("--column", o->column,
                  "Acceleration column (m/s^2) by header name; accel_x/y/z stand for ax/ay/az_m_s2")
      ->type_name("NAME")
      ->capture_default_str();
  add_number_option(cmd, "--rate", &o->rate_hz, "HZ", "Sample rate, Hz (0: from the time column)")
      ->check(non_negative_number());
  add_number_option(cmd, "--window-s", &o->window_s, "S", "Analyse the last S seconds (0: the whole file)")
      ->check(non_negative_number());
  add_number_option(cmd, "--resonance-hz", &o->resonance_hz, "HZ",
                    "Centre of the envelope band, Hz (0: from 4x the highest fault frequency to 0.4x the rate)")
      ->check(non_negative_number());
  add_number_option(cmd, "--band-width-hz", &o->band_width_hz, "HZ", "Envelope band width around --resonance-hz, Hz")
      ->check(positive_number());
  add_vector_option(cmd, "--zones", &o->zones, {"AB", "BC", "CD"},
                    "Velocity zone boundaries, mm/s (default ISO 20816-3 group 2, rigid foundation)");
  add_number_option(cmd, "--snr-db", &o->snr_db, "DB",
                    "Envelope SNR at a fault frequency for a suspected defect, 0-60 dB");
  add_number_option(cmd, "--kurtosis-warn", &o->kurtosis_warn, "K", "Kurtosis for a WARN, 3-1000 (0: off)");
  add_json_flag(cmd, &o->json);
  cmd->callback([o] { run(*o); });
}

}  // namespace bearing_sim::tool
