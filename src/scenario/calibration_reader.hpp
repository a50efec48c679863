#pragma once
// Reads a calibration file (YAML; keys in docs/calibration.md, "The calibration file")
// into a doe::CalibrationSpec, with the scenario reader's located messages: every
// problem as "file:line:column: key.path: message", all of them at once.
#include <string>

#include "doe/calibration_spec.hpp"
#include "doe/envelope_spec.hpp"

namespace regodem {

/// Throws InputError naming every problem found (one per line), or the file that
/// cannot be read. Scenario paths are relative to the calibration file and come back
/// absolute; they must exist.
doe::CalibrationSpec read_calibration_file(const std::string& path);

/// The same for text in memory; `file_name_for_messages` also anchors relative paths.
doe::CalibrationSpec read_calibration_string(const std::string& yaml_text, const std::string& file_name_for_messages);

/// An envelope file (`regodem envelope`; docs/drilling-heat.md), read the same way.
doe::EnvelopeSpec read_envelope_file(const std::string& path);
doe::EnvelopeSpec read_envelope_string(const std::string& yaml_text, const std::string& file_name_for_messages);

}  // namespace regodem
