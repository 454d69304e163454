"""Parameter sweeps: the Cartesian product of scenario variants, run on a Dask cluster.

:mod:`rancf.sweep.spec` reads ``SWEEP.toml``; :mod:`rancf.sweep.runner` runs one variant in a
worker (its own folder, a result row); :mod:`rancf.sweep.engine` schedules them, resumes, and
writes ``results.csv``.
"""
