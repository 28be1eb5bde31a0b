#!/usr/bin/python3
"""Every ctest test carries exactly one tier label (cmake/test_tiers.cmake).

  tests/test_tiers_check.py BUILD_DIR     reads `ctest --show-only=json-v1` in BUILD_DIR
  tests/test_tiers_check.py --self-test   the check fails on a test without a tier or with two

Prints each test without a tier label or with more than one, and the count of tests per tier.
Exits 1 when there is any such test, or when ctest lists no tests at all.
"""
import json
import subprocess
import sys

TIERS = ("quick", "rtl", "regress", "fuzz", "slow")


def labels_of(test):
    for prop in test.get("properties", []):
        if prop.get("name") == "LABELS":
            return list(prop.get("value") or [])
    return []


def check(listing):
    """Returns (problems, counts) for ctest's json-v1 listing."""
    problems = []
    counts = {t: 0 for t in TIERS}
    tests = listing.get("tests", [])
    if not tests:
        problems.append("ctest lists no tests")
    for test in tests:
        name = test.get("name", "?")
        tiers = [l for l in labels_of(test) if l in TIERS]
        if len(tiers) == 0:
            problems.append(f"{name}: no tier label (labels {labels_of(test)}); add a rule to "
                            "cmake/test_tiers.cmake")
        elif len(tiers) > 1:
            problems.append(f"{name}: {len(tiers)} tier labels {tiers}; exactly one allowed")
        else:
            counts[tiers[0]] += 1
    return problems, counts


def self_test():
    def t(name, labels):
        props = [{"name": "LABELS", "value": labels}] if labels is not None else []
        return {"name": name, "properties": props}
    good = {"tests": [t("a", ["quick"]), t("b", ["regress", "coverage"])]}
    no_tier = {"tests": [t("a", ["quick"]), t("b", None), t("c", ["coverage"])]}
    two = {"tests": [t("a", ["quick", "rtl"])]}
    ok = True
    p, counts = check(good)
    ok &= not p and counts["quick"] == 1 and counts["regress"] == 1
    p, _ = check(no_tier)
    ok &= len(p) == 2 and p[0].startswith("b:") and p[1].startswith("c:")
    p, _ = check(two)
    ok &= len(p) == 1 and "2 tier labels" in p[0]
    p, _ = check({"tests": []})
    ok &= p == ["ctest lists no tests"]
    print("self-test: " + ("the check fails on missing and doubled tiers" if ok else "FAILED"))
    return 0 if ok else 1


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    if sys.argv[1] == "--self-test":
        return self_test()
    out = subprocess.run(["ctest", "--show-only=json-v1"], cwd=sys.argv[1], check=True,
                         capture_output=True, text=True).stdout
    problems, counts = check(json.loads(out))
    for p in problems:
        print("FAIL  " + p)
    print("tests per tier: " + ", ".join(f"{t} {counts[t]}" for t in TIERS))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
