"""Reads accelcal's OCP Test & Validation artifacts back through the ocptv package (issue 41).

For each file: the run is written again with ocptv's own writer (TestRun, Dut, steps, measurements
with ocptv's Validator from the spec's limits, the self-test's from the datasheet's +-14 %), from the
names, values and units accelcal's artifacts carry; ocptv checks every field's type as it writes.
Its artifacts must equal accelcal's line for line, but for the timestamps. Prints one JSON summary per
file.

Usage: python3 ocp_reads.py SPEC.json RUN.ocp.jsonl...   (SPEC: {name: [low, high]})
"""

import json
import sys

import ocptv.output as tv
from ocptv.output import TestResult, TestStatus, Validator, ValidatorType

SELF_TEST_LIMIT = 14.0


class Lines:
    def __init__(self):
        self.lines = []

    def write(self, buffer):
        self.lines.append(json.loads(buffer))


def validators(spec, name):
    limits = [-SELF_TEST_LIMIT, SELF_TEST_LIMIT] if name.endswith("_deviation_percent") else spec.get(name)
    if limits is None:
        return []
    found = []
    if limits[0] is not None:
        found.append(Validator(type=ValidatorType.GREATER_THAN_OR_EQUAL, value=limits[0]))
    if limits[1] is not None:
        found.append(Validator(type=ValidatorType.LESS_THAN_OR_EQUAL, value=limits[1]))
    return found


def rewrite(spec, ours):
    """The same run through ocptv's writer; (its artifacts, the measurements of step "fit")."""
    written = Lines()
    tv.config(writer=written)
    start = ours[1]["testRunArtifact"]["testRunStart"]
    run = tv.TestRun(name=start["name"], version=start["version"], command_line=start["commandLine"], parameters=start["parameters"])
    dut = start["dutInfo"]
    run.start(dut=tv.Dut(id=dut["dutInfoId"], name=dut["name"]))
    steps, step, fit = {}, None, {}
    for artifact in ours[2:]:
        if "testStepArtifact" in artifact:
            body = artifact["testStepArtifact"]
            if "testStepStart" in body:
                step = run.add_step(body["testStepStart"]["name"])
                steps[body["testStepId"]] = body["testStepStart"]["name"]
                step.start()
            elif "measurement" in body:
                m = body["measurement"]
                step.add_measurement(name=m["name"], value=m["value"], unit=m.get("unit"), validators=validators(spec, m["name"]))
                if steps[body["testStepId"]] == "fit":
                    fit[m["name"]] = [m["value"], m.get("unit"), [[v["type"], v["value"]] for v in m["validators"]]]
            elif "testStepEnd" in body:
                step.end(status=TestStatus[body["testStepEnd"]["status"]])
        elif "testRunEnd" in artifact.get("testRunArtifact", {}):
            end = artifact["testRunArtifact"]["testRunEnd"]
            run.end(status=TestStatus[end["status"]], result=TestResult[end["result"]])
    return written.lines, fit, start


def main():
    spec = json.load(open(sys.argv[1]))
    for path in sys.argv[2:]:
        ours = [json.loads(line) for line in open(path)]
        theirs, fit, start = rewrite(spec, ours)
        for line in theirs + ours:
            assert "timestamp" in line, line
            del line["timestamp"]
        if theirs != ours:
            for k, (t, o) in enumerate(zip(theirs, ours)):
                if t != o:
                    print(f"{path}: line {k}: ocptv {json.dumps(t)} accelcal {json.dumps(o)}", file=sys.stderr)
            print(f"{path}: ocptv wrote {len(theirs)} lines, accelcal {len(ours)}", file=sys.stderr)
            sys.exit(1)
        result = ours[-1]["testRunArtifact"]["testRunEnd"]["result"]
        print(json.dumps({"dut_id": start["dutInfo"]["dutInfoId"], "station_id": start["parameters"]["station"], "outcome": result, "fit": fit}))


main()
