"""Ready-made car scenarios (what ``make straight`` / ``make slalom`` run).

``python -m flexpipe.scenarios straight --out out/straight``: the sample sedan on an
ISO 8608 class C road at 70 km/h for 10 s, rigid and flexible body;
``python -m flexpipe.scenarios slalom --out out/slalom``: an 8-cone, 18 m, 0.8 m offset
slalom at 60 km/h on a class B road.  Each writes ``rigid.csv``, ``flexible.csv``,
``hub_force_fl.png`` (and ``trajectory.png`` for the slalom) and ``summary.json``.
"""

from flexpipe.scenarios.runner import SCENARIOS, Scenario, run_pair, run_scenario

__all__ = ["SCENARIOS", "Scenario", "run_pair", "run_scenario"]
