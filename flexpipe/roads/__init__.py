"""Roads: heights under the wheel tracks as a function of distance along the path.

Generators (:func:`flat`, :func:`harmonic`, :func:`irregularity`, :func:`iso8608`), readers
(:func:`read_csv`, :func:`read_crg`, :func:`read_rdf` for Adams 2D road files), a writer
(:func:`write_crg`) and :func:`load_road`, which dispatches on ``.crg`` / ``.csv`` /
``.rdf`` / ``.toml``.  All return a frozen :class:`Road`
whose :meth:`Road.height` is vectorized and cheap for scalars.
"""

from flexpipe.roads.crg import read_crg, write_crg
from flexpipe.roads.generators import (
    ISO8608_BAND,
    ISO8608_GD0,
    ISO8608_N0,
    checked_coherence,
    flat,
    harmonic,
    irregularity,
    iso8608,
    iso8608_psd,
    isotropic_coherence,
    track_coherence,
)
from flexpipe.roads.rdf import read_rdf
from flexpipe.roads.road import Road, read_csv
from flexpipe.roads.spec import ROAD_TYPES, load_road, road_from_spec

__all__ = [
    "ISO8608_BAND",
    "ISO8608_GD0",
    "ISO8608_N0",
    "ROAD_TYPES",
    "Road",
    "checked_coherence",
    "flat",
    "harmonic",
    "irregularity",
    "iso8608",
    "iso8608_psd",
    "isotropic_coherence",
    "load_road",
    "read_crg",
    "read_csv",
    "read_rdf",
    "road_from_spec",
    "track_coherence",
    "write_crg",
]
