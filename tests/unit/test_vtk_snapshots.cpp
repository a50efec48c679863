// ParaView snapshots: wall tessellation, .pvd collections, the .vtp layout, the
// snapshot schedule and scenario keys, and a read-back of real runs' files with VTK
// itself (Debian's python3-vtk9, tests/vtk/check_vtk_snapshots.py).
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "geometry/wall_tessellation.hpp"
#include "io/pvd_writer.hpp"
#include "io/snapshot_series.hpp"
#include "io/vtp_writer.hpp"
#include "scenario/scenario_builder.hpp"
#include "scenario/scenario_reader.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot_capture.hpp"
#include "sim/snapshot_schedule.hpp"
#include "sim/stage_plan.hpp"

namespace regodem {
namespace {

namespace fs = std::filesystem;

constexpr int kSkipCode = 77;  // the checker's "python3-vtk9 is not installed"

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("regodem_vtk_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

double triangle_area(const WallSurface& s, std::size_t t) {
  const auto& tri = s.triangles[t];
  return 0.5 * norm(cross(s.points_m[tri[1]] - s.points_m[tri[0]], s.points_m[tri[2]] - s.points_m[tri[0]]));
}

Vec3 triangle_normal(const WallSurface& s, std::size_t t) {
  const auto& tri = s.triangles[t];
  return normalized(cross(s.points_m[tri[1]] - s.points_m[tri[0]], s.points_m[tri[2]] - s.points_m[tri[0]]));
}

// ---------------------------------------------------------------------------------
// Tessellation

TEST(WallTessellation, PlaneOnABoxFaceIsTheWholeFace) {
  WallSet walls;
  walls.add_body("floor", {});
  walls.add_plane(0, {0, 0, 0}, {0, 0, 1}, 0);
  const WallSurface s = tessellate_walls(walls, {-1, -2, 0}, {1, 2, 3});
  double area = 0.0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    area += triangle_area(s, t);
    EXPECT_NEAR(triangle_normal(s, t).z, 1.0, 1e-12) << "triangles face the particles";
  }
  EXPECT_NEAR(area, 2.0 * 4.0, 1e-12);
}

TEST(WallTessellation, TiltedPlaneIsClippedToTheBox) {
  const Vec3 normal = normalized(Vec3{1, 1, 1});
  const std::vector<Vec3> polygon = clip_plane_to_box({0, 0, 0}, normal, {-1, -1, -1}, {1, 1, 1});
  ASSERT_EQ(polygon.size(), 6u) << "a plane through the centre of a cube, normal along a diagonal: a hexagon";
  for (const Vec3& p : polygon) {
    EXPECT_NEAR(dot(p, normal), 0.0, 1e-12);
    for (int axis = 0; axis < 3; ++axis) EXPECT_LE(std::abs(p[axis]), 1.0 + 1e-12);
  }
  EXPECT_TRUE(clip_plane_to_box({0, 0, 5}, {0, 0, 1}, {-1, -1, -1}, {1, 1, 1}).empty()) << "misses the box";
}

TEST(WallTessellation, DiskAndCylinderAreasAndNormals) {
  WallSet walls;
  walls.add_body("cup", {});
  // A capped-bottom cylinder: a shell and a disk, one body.
  walls.add_cylinder(0, {0, 0, 0}, {0, 0, 1}, 2.0, 3.0, true, false, true, false, 0);
  const int n = 32;
  const WallSurface s = tessellate_walls(walls, {-5, -5, -5}, {5, 5, 5}, n);
  double shell = 0.0, disk = 0.0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    EXPECT_EQ(s.body[t], 0u);
    const bool is_shell = walls.primitives[s.primitive[t]].shape == PrimitiveShape::cylinder;
    (is_shell ? shell : disk) += triangle_area(s, t);
    if (is_shell) {  // outward: along the radius at the triangle's centre
      const auto& tri = s.triangles[t];
      const Vec3 centre = (s.points_m[tri[0]] + s.points_m[tri[1]] + s.points_m[tri[2]]) / 3.0;
      EXPECT_GT(dot(triangle_normal(s, t), Vec3{centre.x, centre.y, 0.0}), 0.0);
    }
  }
  // Inscribed polygon: n sin(2 pi / n) / 2 R^2 and perimeter 2 n R sin(pi / n).
  EXPECT_NEAR(disk, 0.5 * n * std::sin(2.0 * std::numbers::pi / n) * 4.0, 1e-12);
  EXPECT_NEAR(shell, 2.0 * n * 2.0 * std::sin(std::numbers::pi / n) * 3.0, 1e-12);
}

TEST(WallTessellation, EachSieveSegmentIsItsOwnBody) {
  WallSet walls;
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t body = walls.add_body("sieve[" + std::to_string(k + 1) + "]", {});
    walls.add_sieve_segment(body, {0, 0, 1.0 * k}, {0, 0, 1}, 0.5, 1.0, k == 0, k == 2, k == 0, 0);
  }
  const WallSurface s = tessellate_walls(walls, {-1, -1, -1}, {1, 1, 4}, 16);
  std::vector<int> triangles_of(3, 0);
  for (const std::uint32_t b : s.body) ++triangles_of[b];
  EXPECT_EQ(triangles_of[0], 2 * 16 + 16) << "the capped bottom segment: shell and disk";
  EXPECT_EQ(triangles_of[1], 2 * 16);
  EXPECT_EQ(triangles_of[2], 2 * 16);
}

// ---------------------------------------------------------------------------------
// Collections and documents

TEST(PvdCollection, ListsEveryDataSetAndRefusesTimeGoingBack) {
  const fs::path dir = fresh_directory("pvd");
  PvdCollection pvd(dir / "particles.pvd");
  pvd.add(0.0, "vtk/particles_000000.vtp");
  pvd.add(0.1, "vtk/particles_000001.vtp");
  const std::string text = read_file(dir / "particles.pvd");
  EXPECT_NE(text.find("timestep=\"0.10000000000000001\""), std::string::npos) << text;
  EXPECT_NE(text.find("file=\"vtk/particles_000001.vtp\""), std::string::npos);
  EXPECT_THROW(pvd.add(0.05, "vtk/late.vtp"), std::invalid_argument);
  EXPECT_EQ(read_file(dir / "particles.pvd"), text) << "a refused entry leaves the file as it was";
  fs::remove_all(dir);
}

TEST(VtpDocument, UncompressedArraysSitInTheAppendedBlockAsWritten) {
  const std::vector<Vec3> points = {{1, 2, 3}, {4, 5, 6}};
  const std::vector<double> radius = {0.25, 0.5};
  VtpDocument document(VtpOptions{false});
  document.set_points(points);
  document.add_vertex_per_point();
  document.add_point_data("radius", radius);
  EXPECT_THROW(document.add_point_data("short", std::vector<double>{1.0}), std::invalid_argument);
  const std::string text = document.to_string();
  EXPECT_NE(text.find("NumberOfPoints=\"2\" NumberOfVerts=\"2\""), std::string::npos);
  EXPECT_EQ(text.find("compressor"), std::string::npos);
  // The radius array is the first in the appended block: a UInt64 byte count, then the doubles.
  const std::size_t data = text.find("encoding=\"raw\">\n   _") + std::strlen("encoding=\"raw\">\n   _");
  const auto offset_at = text.find("Name=\"radius\"");
  const std::size_t offset = std::stoul(text.substr(text.find("offset=\"", offset_at) + 8));
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, text.data() + data + offset, sizeof bytes);
  ASSERT_EQ(bytes, 2 * sizeof(double));
  double values[2];
  std::memcpy(values, text.data() + data + offset + 8, sizeof values);
  EXPECT_EQ(values[0], 0.25);
  EXPECT_EQ(values[1], 0.5);
}

// ---------------------------------------------------------------------------------
// Schedule and scenario keys

TEST(SnapshotClock, ByTimeKeepsToItsGridAndNeverRepeatsATime) {
  SnapshotSchedule schedule;
  schedule.trigger = SnapshotSchedule::Trigger::time;
  schedule.interval_s = 0.1;
  SnapshotClock clock(schedule);
  EXPECT_TRUE(clock.due(0.0, 0.005)) << "the initial state";
  clock.taken(0.0, 0.005);
  EXPECT_FALSE(clock.due(0.0, 0.005));
  EXPECT_FALSE(clock.due(0.09, 0.005));
  EXPECT_TRUE(clock.due(0.096, 0.005)) << "within half a step of 0.1 s";
  clock.taken(0.096, 0.005);
  EXPECT_FALSE(clock.due(0.101, 0.005)) << "the one at 0.096 s was the one due at 0.1 s";
  EXPECT_TRUE(clock.due_at_stage_end(0.15));
  clock.taken(0.15, 0.0);  // a stage end between two regular ones
  EXPECT_TRUE(clock.due(0.2, 0.005)) << "the grid stays 0.1, 0.2, ...";
  EXPECT_FALSE(clock.due_at_stage_end(0.15));
}

TEST(SnapshotClock, BySteps) {
  SnapshotSchedule schedule;
  schedule.trigger = SnapshotSchedule::Trigger::steps;
  schedule.every_steps = 3;
  SnapshotClock clock(schedule);
  clock.taken(0.0, 0.0);
  for (int k = 1; k <= 3; ++k) {
    EXPECT_FALSE(clock.due(0.01 * k, 0.0));
    clock.count_step();
  }
  EXPECT_TRUE(clock.due(0.03, 0.0));
  EXPECT_FALSE(SnapshotClock(SnapshotSchedule{}).due(0.0, 0.0)) << "no schedule, no snapshots";
}

std::string scenario_with_snapshots(const std::string& block) {
  std::string text = read_file(fs::path(REGODEM_SOURCE_DIR) / "tests/data/scenarios/minimal.yaml");
  return text + "output:\n  snapshots: " + block + "\n";
}

TEST(SnapshotKeys, ReadByTimeOrBySteps) {
  const ScenarioSpec by_time = read_scenario_string(scenario_with_snapshots("{interval: 5 ms, compress: false}"), "s.yaml");
  EXPECT_TRUE(by_time.output.snapshots.enabled);
  EXPECT_DOUBLE_EQ(by_time.output.snapshots.interval_s, 0.005);
  EXPECT_FALSE(by_time.output.snapshots.compress);
  EXPECT_TRUE(by_time.output.snapshots.walls);
  const ScenarioSpec by_steps = read_scenario_string(scenario_with_snapshots("{every_steps: 2e3, walls: false}"), "s.yaml");
  EXPECT_EQ(by_steps.output.snapshots.every_steps, 2000u);
  EXPECT_FALSE(by_steps.output.snapshots.walls);
  EXPECT_FALSE(read_scenario_string(scenario_with_snapshots("{interval: 1 s}"), "s.yaml").output.snapshots.every_steps);
}

std::string error_of(const std::string& text) {
  try {
    read_scenario_string(text, "s.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SnapshotKeys, BadValuesAreNamedWithTheirLine) {
  EXPECT_NE(error_of(scenario_with_snapshots("{interval: -1 s}")).find("output.snapshots.interval"),
            std::string::npos);
  EXPECT_NE(error_of(scenario_with_snapshots("{interval: 3 mm}")).find("output.snapshots.interval"),
            std::string::npos);
  EXPECT_NE(error_of(scenario_with_snapshots("{every_steps: 0}")).find("must be 1 or more"), std::string::npos);
  EXPECT_NE(error_of(scenario_with_snapshots("{every_steps: 2.5}")).find("whole number"), std::string::npos);
  EXPECT_NE(error_of(scenario_with_snapshots("{interval: 1 s, every_steps: 10}")).find("only one of"),
            std::string::npos);
  EXPECT_NE(error_of(scenario_with_snapshots("{compress: true}")).find("give one of them"), std::string::npos);
  EXPECT_NE(error_of(scenario_with_snapshots("{interval: 1 s, colour: red}")).find("colour"), std::string::npos);
  EXPECT_NE(error_of(scenario_with_snapshots("{interval: 1 s}")).find("(no error)"), std::string::npos);
}

// ---------------------------------------------------------------------------------
// A real run, read back with VTK

nlohmann::json vec3_list(std::span<const Vec3> values) {
  nlohmann::json out = nlohmann::json::array();
  for (const Vec3& v : values) out.push_back({v.x, v.y, v.z});
  return out;
}

/// Writes the snapshots of a run and records what it wrote, for the Python checker.
class RecordingObserver final : public RunObserver {
 public:
  RecordingObserver(const fs::path& directory, bool compress, std::vector<std::string> region_names)
      : writer_(directory, VtpOptions{compress}, true, std::move(region_names)) {}

  void snapshot(const Simulation& sim) override {
    const ParticleSnapshot p = writer_.particle_snapshot(sim);
    nlohmann::json record;
    record["time"] = p.time_s;
    record["step"] = p.step;
    record["count"] = p.position_m.size();
    record["material_names"] = p.material_names;
    record["region_names"] = p.region_names;
    nlohmann::json& f = record["fields"];
    f["id"] = std::vector<ParticleId>(p.id.begin(), p.id.end());
    f["radius"] = std::vector<double>(p.radius_m.begin(), p.radius_m.end());
    f["temperature"] = std::vector<double>(p.temperature_K.begin(), p.temperature_K.end());
    f["velocity"] = vec3_list(p.velocity_m_per_s);
    f["angular_velocity"] = vec3_list(p.angular_velocity_rad_per_s);
    f["material"] = std::vector<MaterialIndex>(p.material.begin(), p.material.end());
    f["region"] = std::vector<RegionTag>(p.region.begin(), p.region.end());
    f["contacts"] = std::vector<std::uint32_t>(p.contacts.begin(), p.contacts.end());
    record["points"] = vec3_list(p.position_m);
    // The counts agree with the force pass's: each touching pair twice, each wall contact once.
    std::uint64_t total = 0;
    for (const std::uint32_t c : p.contacts) total += c;
    const ContactStatistics& stats = sim.contact_statistics();
    EXPECT_EQ(total, 2 * stats.particle_contacts + stats.wall_contacts) << "at t = " << p.time_s;
    max_contacts_ = std::max(max_contacts_, total);
    particles_.push_back(record);

    const WallSnapshot w = writer_.wall_snapshot(sim);
    nlohmann::json walls;
    walls["time"] = w.time_s;
    walls["wall_names"] = w.body_names;
    walls["triangles"] = w.surface->triangles.size();
    walls["body_of_triangle"] = w.surface->body;
    walls["body_temperature"] = w.body_temperature_K;  // NaN (adiabatic) becomes null
    walls_.push_back(walls);

    writer_.write(sim);
  }

  nlohmann::json expected() const { return {{"particles", particles_}, {"walls", walls_}}; }
  std::uint64_t max_contacts() const { return max_contacts_; }

 private:
  SimulationSnapshotWriter writer_;
  nlohmann::json particles_ = nlohmann::json::array(), walls_ = nlohmann::json::array();
  std::uint64_t max_contacts_ = 0;
};

int run_checker(const std::vector<std::string>& arguments, std::string& output) {
  std::string command = "/usr/bin/python3 '" REGODEM_SOURCE_DIR "/tests/vtk/check_vtk_snapshots.py'";
  for (const std::string& a : arguments) command += " '" + a + "'";
  command += " 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return -1;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void run_and_read_back(bool compress) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 is missing (scripts/setup-debian.sh)";
  const fs::path dir = fresh_directory(compress ? "compressed" : "plain");
  const ScenarioSpec spec =
      read_scenario_file(REGODEM_SOURCE_DIR "/tests/data/scenarios/snapshots_small.yaml");
  PreparedRun run = PreparedRun::build(spec, 1);
  RecordingObserver observer(dir, compress, run.plan().region_names);
  std::atomic<bool> stop{false};
  const RunOutcome outcome = run.run(observer, stop);
  ASSERT_TRUE(outcome.completed) << outcome.message;
  EXPECT_GT(observer.max_contacts(), 0u) << "the settled particles touch";
  {
    std::ofstream out(dir / "expected.json");
    out << observer.expected().dump();
  }
  std::string output;
  const int status = run_checker({dir.string(), "--expected", (dir / "expected.json").string()}, output);
  if (status == kSkipCode) GTEST_SKIP() << output;
  EXPECT_EQ(status, 0) << output;
  fs::remove_all(dir);
}

TEST(VtkReadBack, CompressedSnapshotsOfARunReadBackWithVtk) { run_and_read_back(true); }
TEST(VtkReadBack, UncompressedSnapshotsOfARunReadBackWithVtk) { run_and_read_back(false); }

TEST(VtkReadBack, RegodemRunWritesCollectionsThatVtkReads) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 is missing (scripts/setup-debian.sh)";
  const fs::path dir = fresh_directory("cli");
  const std::string command = std::string("'") + REGODEM_BINARY + "' run '" REGODEM_SOURCE_DIR
                              "/tests/data/scenarios/snapshots_small.yaml' --threads 1 --overwrite -o '" +
                              dir.string() + "' > '" + (dir / "log.txt").string() + "' 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_file(dir / "log.txt");
  std::string output;
  const int status = run_checker({dir.string(), "--summary", (dir / "summary.json").string()}, output);
  if (status == kSkipCode) GTEST_SKIP() << output;
  EXPECT_EQ(status, 0) << output;
  // --overwrite replaces a previous run's snapshots rather than mixing two runs.
  ASSERT_EQ(std::system(command.c_str()), 0) << read_file(dir / "log.txt");
  output.clear();
  EXPECT_EQ(run_checker({dir.string(), "--summary", (dir / "summary.json").string()}, output), 0) << output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace regodem

namespace regodem {
namespace {

// A bonded pair: each particle's snapshot shows one intact bond; without bonds the
// field is absent (not zeros).
TEST(SnapshotCapture, IntactBondsPerParticle) {
  MaterialTable materials;
  Material grain;
  grain.name = "grain";
  grain.density_kg_per_m3 = 2500.0;
  grain.shear_modulus_Pa = 1e8;
  grain.poisson_ratio = 0.25;
  materials.add(grain);
  materials.set_pair(0, 0, PairProperties{});
  SimulationSettings settings;
  settings.domain = {{-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}};
  settings.gravity_m_per_s2 = {};
  settings.time_step_s = 1e-7;
  settings.neighbor_skin_m = 2e-4;
  settings.min_particle_radius_m = 1e-3;
  for (const bool bonded : {false, true}) {
    Simulation sim(materials, WallSet{}, settings);
    for (const double x : {-1e-3, 1e-3, 5e-3}) {
      NewParticle p;
      p.position_m = {x, 0.0, 0.0};
      p.radius_m = 1e-3;
      p.density_kg_per_m3 = 2500.0;
      sim.add_particle(p);
    }
    if (bonded) {
      BondParameters bond;
      bond.normal_stiffness_Pa_per_m = 1e11;
      bond.shear_stiffness_Pa_per_m = 4e10;
      bond.tensile_strength_Pa = 1e6;
      bond.shear_strength_Pa = 1e6;
      sim.configure_bonds({bond}, {0});
      ASSERT_EQ(sim.form_bonds(0.01), 1u);
    }
    sim.step();
    SimulationSnapshotWriter writer(std::filesystem::temp_directory_path() / "regodem-bond-snapshot", VtpOptions{},
                                    false, {});
    const ParticleSnapshot snap = writer.particle_snapshot(sim);
    if (!bonded) {
      EXPECT_TRUE(snap.intact_bonds.empty());
      continue;
    }
    ASSERT_EQ(snap.intact_bonds.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i)
      EXPECT_EQ(snap.intact_bonds[i], sim.particles.position_m[i].x > 4e-3 ? 0 : 1) << i;
  }
  std::filesystem::remove_all(std::filesystem::temp_directory_path() / "regodem-bond-snapshot");
}

}  // namespace
}  // namespace regodem
