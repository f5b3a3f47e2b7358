"""Half-car study of Verros, Goudas, Natsiavas & Hache (beam body, CMS, ride spectra).

See ``flexpipe/halfcar/README.md`` for the model, the parameter set and the methods.
"""

from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.hb import HarmonicBalance, PeriodicSolution, sweep
from flexpipe.halfcar.linear import Spectrum, frequency_response, linear_spectrum
from flexpipe.halfcar.model import VARIANTS, HalfCarModel, build_model, natural_frequencies
from flexpipe.halfcar.params import HalfCarParams, load_params
from flexpipe.halfcar.transient import Road, Transient, simulate

__all__ = ["VARIANTS", "HalfCarModel", "HalfCarParams", "HarmonicBalance", "Nonlinearity",
           "PeriodicSolution", "Road", "Spectrum", "Transient", "build_model",
           "frequency_response", "linear_spectrum", "load_params", "natural_frequencies",
           "simulate", "sweep"]
