"""The spray (docs/model.md §20): the spot models, the deposition model, the part's shade on
it, the steps where a shadow edge passes."""
from .deposition import Gun, deposition_rate, film
from .spots import SPOTS, BetaSpot, EllipticGaussian, RoundGaussian, Spot

__all__ = ["SPOTS", "BetaSpot", "EllipticGaussian", "Gun", "RoundGaussian", "Spot",
           "deposition_rate", "film"]
