"""One driver per analysis: a scenario in, a result out.

The command line (:mod:`rancf.cli`), the Python API, sweeps (:mod:`rancf.sweep`) and the shipped
examples (:mod:`rancf.studies`) call these and nothing else, so the same scenario gives the same
numbers whichever way it is run:

* :func:`rancf.runs.modes.run_modes`: natural modes about the reference or the static state,
  and the Campbell diagram when ``[modes] spin_rates`` is given
  (:func:`rancf.runs.campbell.run_campbell`);
* :func:`rancf.runs.buckling.run_buckling`: linearized buckling load factors;
* :func:`rancf.runs.static.run_static`: the static equilibrium along the load path (and the
  load path as a run folder);
* :func:`rancf.runs.simulate.run_simulate`: the dynamics, held in memory (``rancf simulate``
  streams its rows to disk through the same steps, :mod:`rancf.runs.simulate`).
"""
