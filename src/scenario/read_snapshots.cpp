// The `output.snapshots` block: when a run writes ParaView snapshots (particles and
// walls as .vtp, listed in .pvd collections) and in what form.
#include <fmt/format.h>

#include "scenario/scenario_fields.hpp"
#include "scenario/scenario_sections.hpp"

namespace regodem {

void read_snapshots(const YamlValue& value, OutputSpec& output) {
  const auto section = value.section();
  if (!section) return;
  section->allow_only({"interval", "every_steps", "every_depth", "at_stage_end", "walls", "compress"},
                      {{"every", "'every_steps' counts steps; 'interval' is simulated time"},
                       {"steps", "'every_steps' counts steps; 'interval' is simulated time"}});
  SnapshotSpec& snapshots = output.snapshots;
  snapshots.where = value.where();
  const auto trigger = section->exactly_one_of({"interval", "every_steps", "every_depth"});
  if (trigger == "interval") {
    if (const auto interval = read_checked_quantity(*section, "interval", Dimension::time, Presence::required,
                                                    is_positive, "be greater than 0")) {
      snapshots.enabled = true;
      snapshots.interval_s = *interval;
    }
  } else if (trigger == "every_steps") {
    const YamlValue steps = *section->get("every_steps");
    if (const auto count = steps.whole_number()) {
      if (*count == 0) {
        steps.error("must be 1 or more (steps between snapshots)");
      } else {
        snapshots.enabled = true;
        snapshots.every_steps = *count;
      }
    }
  }
  if (trigger == "every_depth") {
    // every_depth: {wall: drill, depth: 1 mm}, the wall's depth as its motion defines it.
    if (const auto depth = section->get("every_depth")->section()) {
      depth->allow_only({"wall", "depth"});
      const auto wall = depth->require("wall");
      const auto step = read_checked_quantity(*depth, "depth", Dimension::length, Presence::required, is_positive,
                                              "be greater than 0");
      if (wall && step) {
        snapshots.enabled = true;
        snapshots.depth_wall = wall->text().value_or("");
        snapshots.depth_interval_m = *step;
      }
    }
  }
  snapshots.at_stage_end = section->boolean("at_stage_end").value_or(snapshots.at_stage_end);
  snapshots.walls = section->boolean("walls").value_or(snapshots.walls);
  snapshots.compress = section->boolean("compress").value_or(snapshots.compress);
}

}  // namespace regodem
