// simulate_and_map: the paper's benchmark for one run, step by step. Obstacle course 4, table
// test T, seed 1 -> simulated LMS 200 scans -> raw elevation/certainty map (Eq. 1-6) -> CAS and
// the four baselines -> PI (Eq. 11) against the exact ground truth. Prints the same PI line as
// `casmap bench --courses 4 --tests T --seed 1`.
//
//   simulate_and_map [COURSE] [TEST]      (defaults: 4 T)
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/pipeline/bench_runner.hpp"

namespace cm = casmap;

int main(int argc, char** argv) {
    const int course_number = argc > 1 ? std::atoi(argv[1]) : 4;
    const std::string test = argc > 2 ? argv[2] : "T";
    try {
        // 1. The installed scenes/courses, default rig and sensor, seed 1.
        const cm::pipeline::BenchSettings settings =
            cm::pipeline::ResolveBenchSettings("", "", "", 1);
        const cm::pipeline::SimSetup setup =
            cm::pipeline::BenchSetup(settings, course_number, test);

        // 2. The course: scene, ray-casting world and ground truth on the paper's 200 x 80 grid.
        const std::vector<cm::pipeline::Course> courses =
            cm::pipeline::LoadCourses(settings, {course_number}, setup.grid, 1);
        const cm::pipeline::Course& course = courses.front();

        // 3. The table moves the scanner (test T: straight at 1 m/s); simulate and map.
        const cm::core::Trajectory poses = cm::pipeline::RigTrajectory(setup, course.scene);
        const cm::pipeline::MappedBenchRun run =
            cm::pipeline::SimulateAndMap(setup, course, poses, /*a=*/3);
        const cm::core::MapF& raw = run.mapped.elevation;

        // 4. The five filters with the parameters the run implies (Eq. 8: A from s, v, dt, a),
        //    each scored by Eq. 11 over the paper's N x M region.
        const cm::mapper::FilterParams params = cm::pipeline::RunFilterParams(run, {});
        const cm::mapper::Region region = cm::mapper::PaperRegion(raw.rows, raw.cols);
        cm::pipeline::BenchRun scores;
        scores.course = course_number;
        scores.test = test;
        for (const cm::mapper::FilterMethod method : cm::mapper::AllFilterMethods()) {
            const cm::mapper::FilterResult filtered =
                cm::mapper::RunFilter(method, raw, run.mapped.certainty, params);
            scores.filters[std::string(cm::mapper::ToString(method))].pi =
                cm::mapper::PerformanceIndex(filtered.elevation, raw, course.truth, region);
        }

        // 5. The table `casmap bench` prints (header + one line per run).
        std::fputs(cm::pipeline::PiTable({scores}).c_str(), stdout);
        return 0;
    } catch (const cm::InputError& e) {
        std::fprintf(stderr, "simulate_and_map: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "simulate_and_map: error: %s\n", e.what());
        return 1;
    }
}
