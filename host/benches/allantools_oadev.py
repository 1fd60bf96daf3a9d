"""Times allantools' oadev on the six axes the Rust bench wrote (raw little-endian f64, one axis after
another), at the same averaging times: the median CPU time (time.process_time) of `repeats` runs;
prints JSON with the seconds and the deviations."""
import json
import sys
import time

import allantools
import numpy

path, rate, samples = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
taus, repeats = numpy.array(json.loads(sys.argv[4])), int(sys.argv[5])
axes = numpy.fromfile(path, dtype="<f8").reshape(6, samples)
seconds = []
for _ in range(repeats):
    began = time.process_time()
    adevs = [allantools.oadev(axis, rate=rate, data_type="freq", taus=taus)[1] for axis in axes]
    seconds.append(time.process_time() - began)
print(json.dumps({"seconds": sorted(seconds)[len(seconds) // 2], "adev": [list(a) for a in adevs]}))
