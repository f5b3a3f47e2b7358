"""Half-car study of Verros, Goudas, Natsiavas & Hache (beam body, CMS, ride spectra)."""

from flexpipe.halfcar.model import VARIANTS, HalfCarModel, build_model, natural_frequencies
from flexpipe.halfcar.params import HalfCarParams, load_params

__all__ = ["VARIANTS", "HalfCarModel", "HalfCarParams", "build_model", "load_params",
           "natural_frequencies"]
