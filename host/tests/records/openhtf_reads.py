"""Reads accelcal's OpenHTF JSON test records back through OpenHTF's own classes (issue 41).

For each record: a TestRecord, its PhaseRecords and their Measurements are built with openhtf's own
classes from the record's ids and values, each measurement's units as the record names them and its
in_range validator from the spec's limits (the self-test's from the datasheet's +-14 %), validated by
openhtf; then openhtf serialises the record as its JSON output does (data.convert_to_base_types) and
it must equal accelcal's record field for field. Prints one JSON summary per record.

Usage: python3 openhtf_reads.py SPEC.json RECORD.openhtf.json...   (SPEC: {name: [low, high]})
"""

import json
import sys

from openhtf.core import measurements, test_record
from openhtf.util import data, units

SELF_TEST_LIMIT = 14.0


def limits_of(spec, name):
    if name.endswith("_deviation_percent"):
        return [-SELF_TEST_LIMIT, SELF_TEST_LIMIT]
    return spec.get(name)


def measurement(spec, name, ours):
    meas = measurements.Measurement(name)
    if "units" in ours:
        u = ours["units"]
        meas = meas.with_units(units.UnitDescriptor(u["name"], u["code"], u["suffix"]))
    limits = limits_of(spec, name)
    if limits is not None:
        meas = meas.in_range(minimum=limits[0], maximum=limits[1])
    meas.measured_value.set(ours["measured_value"])
    meas.validate()
    return meas


def phase(spec, ours):
    record = test_record.PhaseRecord(
        descriptor_id=ours["descriptor_id"],
        name=ours["name"],
        codeinfo=test_record.CodeInfo.uncaptured(),
        start_time_millis=ours["start_time_millis"],
        end_time_millis=ours["end_time_millis"],
    )
    record.measurements = {n: measurement(spec, n, m) for n, m in ours["measurements"].items()}
    outcomes = [m.outcome for m in record.measurements.values()]
    if not outcomes:
        record.outcome = test_record.PhaseOutcome.SKIP
    elif all(o == measurements.Outcome.PASS for o in outcomes):
        record.outcome = test_record.PhaseOutcome.PASS
    else:
        record.outcome = test_record.PhaseOutcome.FAIL
    return record


def read(spec, ours):
    record = test_record.TestRecord(
        dut_id=ours["dut_id"],
        station_id=ours["station_id"],
        start_time_millis=ours["start_time_millis"],
        end_time_millis=ours["end_time_millis"],
        metadata=ours["metadata"],
    )
    for p in ours["phases"]:
        record.add_phase_record(phase(spec, p))
    failed = any(p.outcome == test_record.PhaseOutcome.FAIL for p in record.phases)
    record.outcome = test_record.Outcome.FAIL if failed else test_record.Outcome.PASS
    return record


def main():
    spec = json.load(open(sys.argv[1]))
    for path in sys.argv[2:]:
        ours = json.load(open(path))
        record = read(spec, ours)
        theirs = json.loads(json.dumps(data.convert_to_base_types(record)))
        if theirs != ours:
            for key in sorted(set(theirs) | set(ours)):
                if theirs.get(key) != ours.get(key):
                    print(f"{path}: {key}: openhtf {json.dumps(theirs.get(key))[:400]} accelcal {json.dumps(ours.get(key))[:400]}", file=sys.stderr)
            sys.exit(1)
        fit = next(p for p in record.phases if p.name == "fit")
        shown = {
            n: [m.measured_value.value, m.units.suffix if m.units else None, [str(v) for v in m.validators], m.outcome.name]
            for n, m in fit.measurements.items()
        }
        phases = {p.name: p.outcome.name for p in record.phases}
        print(json.dumps({"dut_id": record.dut_id, "station_id": record.station_id, "outcome": record.outcome.name, "phases": phases, "fit": shown}))


main()
