"""The elastic coupling of the studies that were measured before velocity Verlet became the
default (docs/method.md, "Time step"): their runs keep Algorithm 1's coupling unless a run
names one, so that rerunning them measures what their pages describe."""

ALGORITHM_1 = 'time.elastic_coupling="symplectic_euler"'


def with_coupling(sets):
    """The --set overrides of one run, with Algorithm 1's coupling unless they name one."""
    return list(sets) if any(s.startswith("time.elastic_coupling") for s in sets) else list(sets) + [ALGORITHM_1]
