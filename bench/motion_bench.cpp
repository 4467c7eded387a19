// motion_bench: the motion checks a planner asks for, timed one by one, our checker against FCL.
//
// On MotionBenchMaker problems (the scenes and problems of mbm_bench: the same --seed and
// --problems give the same problems), RRTConnect runs once per problem to its first solution on
// our checker, recording every motion it asks the motion validator about. The recorded motions are
// then replayed, alternating, in --rounds rounds, through OMPL's DiscreteMotionValidator on two
// checkers of the same state space: ours (the convex pieces) and FCL on the original meshes (the
// FclStateValidityChecker of mbm_bench). Both answer the same motions in the same order, so the
// comparison is free of the planner's randomness that mbm_bench's planning times carry. Each motion
// is timed alone and its fastest round kept (the machine is shared: other processes only add time).
// The answers are compared: ours may reject a motion FCL accepts (the pieces contain the meshes and
// stick out by the geometry excess), never the other way round; such motions are counted.
//
// The same motions also go through the certified motion validator (certified_motion_validator.h)
// on our checker, timed the same way, its memo of certified motions emptied before each: what
// proving every motion costs against sampling it. Its verdicts are compared with the discrete
// ones: a motion the discrete check accepts and the certified one rejects either collides between
// the sampled states or passes within tol::kCertifiedResolution of contact (counted).
//
// Output: a table on stdout (per scene: motions, share valid, states per motion and per motion
// tested, mean and median microseconds per motion for the three, the configurations the
// certified validator tested per motion) and bench/results/motion_bench.csv.
// Usage: motion_bench [--problems N] [--rounds R] [--seed S] [--scenes a,b] [--out FILE]

#include "format.h"
#include "mbm_problems.h"
#include "options.h"
#include "plan_problems.h"

#include "deepcheck/fcl_reference/fcl_validity_checker.h"
#include "deepcheck/planners/certified_motion_validator.h"
#include "deepcheck/planners/planner_factory.h"
#include "deepcheck/planners/setup.h"
#include "deepcheck/planners/state_space.h"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace deepcheck::bench;
namespace dp = deepcheck::planners;
namespace ob = ompl::base;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  int problems = 10;
  int rounds = 5;
  unsigned seed = 1;
  std::vector<std::string> scenes;  ///< empty: all
  std::string out = std::string(DEEPCHECK_BENCH_RESULTS_DIR) + "/motion_bench.csv";
};

[[noreturn]] void usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "motion_bench: %s\n", error.c_str());
  std::fprintf(stderr,
               "usage: motion_bench [--problems N] [--rounds R] [--seed S] [--scenes a,b] [--out FILE]\n"
               "  --problems N   MotionBenchMaker problems per scene (default 10; as mbm_bench generates them)\n"
               "  --rounds R     replays of the recorded motions per validator (default 5; fastest kept)\n"
               "  --seed S       seed of problem generation and of OMPL (default 1)\n"
               "  --scenes       mbm_bench's scene names (default all)\n"
               "  --out FILE     CSV (default bench/results/motion_bench.csv)\n");
  std::exit(2);
}

Options parseOptions(int argc, char** argv) {
  Options opt;
  readOptions(argc, argv, usage, [&](const std::string& arg, auto value) {
    if (arg == "--problems") {
      opt.problems = positiveCount(value(), arg, usage);
    } else if (arg == "--rounds") {
      opt.rounds = positiveCount(value(), arg, usage);
    } else if (arg == "--seed") {
      opt.seed = static_cast<unsigned>(std::stoul(value()));
    } else if (arg == "--scenes") {
      opt.scenes = splitList(value());
    } else if (arg == "--out") {
      opt.out = value();
    } else {
      return false;
    }
    return true;
  });
  return opt;
}

using Motion = std::pair<Eigen::VectorXd, Eigen::VectorXd>;

/// Answers with `inner` and records every motion it is asked about.
class RecordingValidator : public ob::MotionValidator {
 public:
  RecordingValidator(ob::SpaceInformation* si, ob::MotionValidatorPtr inner, std::vector<Motion>* motions)
      : ob::MotionValidator(si), inner_(std::move(inner)), motions_(motions) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    motions_->emplace_back(dp::mapState(s1, dim()), dp::mapState(s2, dim()));
    return inner_->checkMotion(s1, s2);
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    motions_->emplace_back(dp::mapState(s1, dim()), dp::mapState(s2, dim()));
    return inner_->checkMotion(s1, s2, lastValid);
  }

 private:
  int dim() const { return static_cast<int>(si_->getStateDimension()); }
  ob::MotionValidatorPtr inner_;
  std::vector<Motion>* motions_;
};

/// The motions RRTConnect asks about on one problem (its first solution, at most 10 s).
std::vector<Motion> recordMotions(const std::shared_ptr<deepcheck::checker::World>& world,
                                  const deepcheck::problems::Problem& problem) {
  auto ss = dp::makeSimpleSetup(world, pandaArmOptions());
  dp::setStartAndGoal(*ss, problem.start, problem.goal);
  const ob::SpaceInformationPtr& si = ss->getSpaceInformation();
  std::vector<Motion> motions;
  si->setMotionValidator(std::make_shared<RecordingValidator>(si.get(), si->getMotionValidator(), &motions));
  ss->setPlanner(dp::makePlanner("RRTConnect", si));
  ss->setup();
  ss->solve(10.0);
  return motions;
}

struct Replay {
  std::vector<double> micros;  ///< per motion, the fastest round
  std::vector<char> valid;
};

/// Times every motion through `validator`, keeping each motion's fastest time over the rounds
/// already in `replay`. A certified validator's memos, when given, are emptied before each motion
/// (untimed): it would otherwise answer a motion of an earlier round from them.
void replayOnce(const ob::MotionValidator& validator, const ob::SpaceInformationPtr& si,
                const std::vector<Motion>& motions, Replay& replay, dp::CertifiedMotionMemo* memo = nullptr,
                dp::CertifiedMotionValidator* certified = nullptr) {
  ob::ScopedState<> s1(si), s2(si);
  if (replay.micros.empty()) {
    replay.micros.assign(motions.size(), 1e300);
    replay.valid.assign(motions.size(), 0);
  }
  for (std::size_t k = 0; k < motions.size(); ++k) {
    dp::copyToState(motions[k].first, s1.get());
    dp::copyToState(motions[k].second, s2.get());
    if (memo != nullptr) memo->clear();
    if (certified != nullptr) certified->forgetRefusedMotions();
    const auto t0 = Clock::now();
    const bool valid = validator.checkMotion(s1.get(), s2.get());
    const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    replay.micros[k] = std::min(replay.micros[k], us);
    replay.valid[k] = valid ? 1 : 0;
  }
}

struct SceneResult {
  std::string scene;
  std::vector<double> ours, certified, fcl;             ///< microseconds per motion
  std::vector<double> oursAccepted, certifiedAccepted;  ///< ... of the motions each accepted
  long states = 0;                                      ///< states of the motions at the space's resolution
  long tested = 0;             ///< states our discrete check tested (motions stop at the first invalid one)
  int valid = 0;               ///< motions valid for our discrete check
  int certifiedValid = 0;      ///< motions the certified validator accepts
  int oursOnlyInvalid = 0;     ///< motions FCL accepts and ours rejects
  int fclOnlyInvalid = 0;      ///< motions ours (either validator) accepts and FCL rejects (must be 0)
  int discreteOnlyValid = 0;   ///< motions the discrete check accepts and the certified one rejects
  int certifiedOnlyValid = 0;  ///< motions the certified validator accepts and the discrete check rejects
  long configurations = 0;     ///< configurations the certified validator tested

  /// Adds another scene's motions (the "all" row).
  void add(const SceneResult& r) {
    ours.insert(ours.end(), r.ours.begin(), r.ours.end());
    certified.insert(certified.end(), r.certified.begin(), r.certified.end());
    oursAccepted.insert(oursAccepted.end(), r.oursAccepted.begin(), r.oursAccepted.end());
    certifiedAccepted.insert(certifiedAccepted.end(), r.certifiedAccepted.begin(), r.certifiedAccepted.end());
    fcl.insert(fcl.end(), r.fcl.begin(), r.fcl.end());
    states += r.states;
    tested += r.tested;
    valid += r.valid;
    certifiedValid += r.certifiedValid;
    oursOnlyInvalid += r.oursOnlyInvalid;
    fclOnlyInvalid += r.fclOnlyInvalid;
    discreteOnlyValid += r.discreteOnlyValid;
    certifiedOnlyValid += r.certifiedOnlyValid;
    configurations += r.configurations;
  }
};

/// Compares the verdicts of the three validators on every motion.
void compareVerdicts(const Replay& discrete, const Replay& certified, const Replay& fcl, SceneResult& result) {
  for (std::size_t k = 0; k < discrete.valid.size(); ++k) {
    result.valid += discrete.valid[k];
    result.certifiedValid += certified.valid[k];
    if (!discrete.valid[k] && fcl.valid[k]) ++result.oursOnlyInvalid;
    if (discrete.valid[k] && !certified.valid[k]) ++result.discreteOnlyValid;
    if (!discrete.valid[k] && certified.valid[k]) ++result.certifiedOnlyValid;
    if ((discrete.valid[k] || certified.valid[k]) && !fcl.valid[k]) {
      ++result.fclOnlyInvalid;
      std::fprintf(stderr, "motion_bench: %s: motion %zu accepted by ours, rejected by FCL\n", result.scene.c_str(), k);
    }
  }
}

/// Replays one problem's motions through our checker (discrete and certified) and FCL's,
/// alternating.
void replayProblem(const std::shared_ptr<deepcheck::checker::World>& world, const std::vector<Motion>& motions,
                   int rounds, SceneResult& result) {
  auto ours = dp::makeSimpleSetup(world, pandaArmOptions());
  std::shared_ptr<deepcheck::fcl_reference::FclStateValidityChecker> fclChecker;
  auto fcl = makeFclSetup(*ours, *world, &fclChecker);
  const ob::SpaceInformationPtr& si = ours->getSpaceInformation();
  const ob::SpaceInformationPtr& fclSi = fcl->getSpaceInformation();
  fclSi->setup();
  const auto checker = dp::validityCheckerOf(*ours);
  ob::DiscreteMotionValidator ourValidator(si);
  dp::CertifiedMotionValidator certifiedValidator(si, checker);
  ob::DiscreteMotionValidator fclValidator(fclSi);
  Replay a, c, b;
  for (int r = 0; r < rounds; ++r) {
    const std::uint64_t before = checker->validityQueries();
    replayOnce(ourValidator, si, motions, a);
    if (r == 0) result.tested += static_cast<long>(checker->validityQueries() - before);
    if (r == 0) certifiedValidator.resetStats();
    replayOnce(certifiedValidator, si, motions, c, &checker->certifiedMotions(), &certifiedValidator);
    if (r == 0) result.configurations += static_cast<long>(certifiedValidator.stats().configurations);
    replayOnce(fclValidator, fclSi, motions, b);
  }
  ob::ScopedState<> s1(si), s2(si);
  for (std::size_t k = 0; k < motions.size(); ++k) {
    dp::copyToState(motions[k].first, s1.get());
    dp::copyToState(motions[k].second, s2.get());
    result.states += std::max(1u, si->getStateSpace()->validSegmentCount(s1.get(), s2.get()));
  }
  compareVerdicts(a, c, b, result);
  result.ours.insert(result.ours.end(), a.micros.begin(), a.micros.end());
  result.certified.insert(result.certified.end(), c.micros.begin(), c.micros.end());
  for (std::size_t k = 0; k < motions.size(); ++k) {
    if (a.valid[k]) result.oursAccepted.push_back(a.micros[k]);
    if (c.valid[k]) result.certifiedAccepted.push_back(c.micros[k]);
  }
  result.fcl.insert(result.fcl.end(), b.micros.begin(), b.micros.end());
}

void printRow(const SceneResult& r) {
  const double n = static_cast<double>(r.ours.size());
  std::printf(
      "| %s | %zu | %.0f %% | %.0f %% | %d | %d | %.1f | %.1f | %s | %s | %s | %s | %s | %s | %.1f | %s | %s |\n",
      r.scene.c_str(), r.ours.size(), 100.0 * r.valid / n, 100.0 * r.certifiedValid / n, r.discreteOnlyValid,
      r.certifiedOnlyValid, r.states / n, r.tested / n, fmt(mean(r.ours)).c_str(), fmt(median(r.ours)).c_str(),
      fmt(mean(r.oursAccepted)).c_str(), fmt(mean(r.certified)).c_str(), fmt(median(r.certified)).c_str(),
      fmt(mean(r.certifiedAccepted)).c_str(), r.configurations / n, fmt(mean(r.fcl)).c_str(),
      fmt(median(r.fcl)).c_str());
}

void writeCsv(const std::string& path, const std::vector<SceneResult>& results) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream out(path);
  out << "scene,validator,motions,valid_share,mean_us,median_us,p90_us,states_per_motion,tested_per_motion,"
         "discrete_only_valid,certified_only_valid,certified_configurations_per_motion\n";
  for (const SceneResult& r : results) {
    const double n = static_cast<double>(r.ours.size());
    const struct {
      const char* name;
      const std::vector<double>* t;
      int valid;
    } rows[] = {{"deepcheck_discrete", &r.ours, r.valid},
                {"deepcheck_certified", &r.certified, r.certifiedValid},
                {"fcl_discrete", &r.fcl, r.valid + r.oursOnlyInvalid}};
    for (const auto& row : rows) {
      out << r.scene << ',' << row.name << ',' << r.ours.size() << ',' << row.valid / n << ',' << mean(*row.t) << ','
          << median(*row.t) << ',' << quantile(*row.t, 0.9) << ',' << r.states / n << ',' << r.tested / n << ','
          << r.discreteOnlyValid << ',' << r.certifiedOnlyValid << ',' << r.configurations / n << '\n';
    }
  }
  std::fprintf(stderr, "wrote %s\n", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parseOptions(argc, argv);
  if (!haveShared()) {
    std::fprintf(stderr, "motion_bench: ../shared is absent (%s): no Panda, no MotionBenchMaker scenes\n",
                 sharedDir().c_str());
    return 1;
  }
  ompl::RNG::setSeed(opt.seed);
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  const auto world = dp::loadWorld(pandaUrdf(), {}, pandaArmOptions());
  std::vector<SceneResult> results;
  for (const MbmScene& scene : selectScenes(opt.scenes, usage)) {
    auto base = dp::makeSimpleSetup(world, pandaArmOptions());
    const deepcheck::problems::ProblemOptions options = pandaProblemOptions(scene, world->robot(), opt.seed, nullptr);
    const std::vector<deepcheck::problems::Problem> problems = generateMbmProblems(
        scene, *world, *dp::validityCheckerOf(*base), options, opt.problems,
        [&](int k, const deepcheck::problems::Problem&) {
          std::fprintf(stderr, "[%s] problem %d/%d generated\n", scene.name.c_str(), k + 1, opt.problems);
        });
    SceneResult result;
    result.scene = scene.name;
    for (std::size_t k = 0; k < problems.size(); ++k) {
      placeScene(*world, problems[k].scene);
      const std::vector<Motion> motions = recordMotions(world, problems[k]);
      replayProblem(world, motions, opt.rounds, result);
      std::fprintf(stderr, "[%s] problem %zu/%zu: %zu motions\n", scene.name.c_str(), k + 1, problems.size(),
                   motions.size());
    }
    for (int id : world->obstacleIds()) world->removeObstacle(id);
    results.push_back(std::move(result));
  }
  std::printf(
      "# Motion checks of RRTConnect on MotionBenchMaker problems (motion_bench)\n\n"
      "%d problem(s) per scene (seed %u), fastest of %d round(s); OMPL's DiscreteMotionValidator on our "
      "checker and on FCL's, and our CertifiedMotionValidator; times in microseconds per motion.\n\n"
      "| scene | motions | valid (discrete) | valid (certified) | discrete only | certified only | "
      "states per motion | tested | discrete: mean | median | mean accepted | certified: mean | median | "
      "mean accepted | configurations | FCL: mean | median |\n"
      "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n",
      opt.problems, opt.seed, opt.rounds);
  SceneResult all;
  all.scene = "all";
  for (const SceneResult& r : results) {
    printRow(r);
    all.add(r);
  }
  if (!all.ours.empty()) printRow(all);
  results.push_back(all);
  writeCsv(opt.out, results);
  const int disagreements = all.fclOnlyInvalid;
  if (disagreements > 0)
    std::fprintf(stderr, "motion_bench: %d motion(s) accepted by ours and rejected by FCL\n", disagreements);
  return disagreements > 0 ? 1 : 0;
}
