#!/usr/bin/env python3
"""Where RRTConnect's time goes with our checker: reads `perf script -F ip,sym` output of an
mbm_bench run recorded with call graphs (bench/run_mbm_profile.sh) and splits the samples taken
inside RRTConnect::solve into categories, each sample counted once, in the first category (in the
order below) one of its stack frames matches. Also prints the share inside motion checks and
state checks, and the top functions by self time.

Usage: mbm_profile.py STACKS.txt
"""
import collections
import re
import sys

CATEGORIES = [
    ("forward kinematics", r"forwardKinematics"),
    ("narrow phase (GJK, kept tetrahedra, centroid test)", r"geometry::|overlapWorld|overlapSelf|overlapPair"),
    ("broad phase (AABB tree, link spheres, piece bounds and poses)",
     r"linkHitsSet|forEachOverlapping|separated|posePiece|BoundsMeet|selfPairHits|forEachSelfPiecePair"),
    ("isFree rest (prepare, last-hit re-test, loops)",
     r"World::isFree|detail::prepare|lastHitStillHits|checkLinkTranslations"),
    ("validity checker wrapper (bounds, state mapping)",
     r"planners::StateValidityChecker|StateMapping|checkConfiguration"),
    ("motion validator interpolation", r"DiscreteMotionValidator|interpolate"),
    ("nearest neighbours (GNAT)", r"NearestNeighbors|GreedyKCenters"),
]
OTHER = "OMPL rest (sampling, tree, allocation)"


def read_samples(path):
    samples, current = [], []
    with open(path, errors="replace") as f:
        for line in f:
            if not line.strip():
                if current:
                    samples.append(current)
                current = []
                continue
            parts = line.strip().split(None, 1)
            current.append(parts[1] if len(parts) == 2 else "?")
    if current:
        samples.append(current)
    return samples


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    samples = [s for s in read_samples(sys.argv[1]) if any("RRTConnect::solve" in f for f in s)]
    n = len(samples)
    if n == 0:
        sys.exit("no sample inside RRTConnect::solve")
    share = lambda k: 100.0 * k / n
    inside = lambda pattern: sum(1 for s in samples if any(pattern in f for f in s))
    print(f"samples inside RRTConnect::solve: {n}")
    print(f"  inside motion checks (DiscreteMotionValidator::checkMotion): {share(inside('checkMotion')):.0f} %")
    print(f"  inside state checks (StateValidityChecker::isValid, motion checks' included): "
          f"{share(inside('planners::StateValidityChecker::isValid')):.0f} %")
    counts = collections.Counter()
    for s in samples:
        for name, pattern in CATEGORIES:
            if any(re.search(pattern, f) for f in s):
                counts[name] += 1
                break
        else:
            counts[OTHER] += 1
    print("\nby category:")
    for name, k in counts.most_common():
        print(f"  {share(k):5.1f} %  {name}")
    print("\ntop functions by self time:")
    for name, k in collections.Counter(s[0] for s in samples).most_common(12):
        print(f"  {share(k):5.1f} %  {re.sub(r'[(].*', '', name.replace('(anonymous namespace)', '{anon}'))[:110]}")


if __name__ == "__main__":
    main()
