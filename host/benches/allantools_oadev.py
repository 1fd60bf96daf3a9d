"""Times allantools' oadev on the six axes the Rust bench wrote (raw little-endian f64, one axis after
another), at the same averaging times; prints JSON with the seconds and the deviations."""
import json
import sys
import time

import allantools
import numpy

path, rate, samples = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
taus = numpy.array(json.loads(sys.argv[4]))
axes = numpy.fromfile(path, dtype="<f8").reshape(6, samples)
began = time.perf_counter()
adevs = [allantools.oadev(axis, rate=rate, data_type="freq", taus=taus)[1] for axis in axes]
seconds = time.perf_counter() - began
print(json.dumps({"seconds": seconds, "adev": [list(a) for a in adevs]}))
