"""The figure groups of `luz figures`, one module each, in the lecture's order."""

from . import (antialias, assignment, bounding, colour, distance, global_models, lambert,
               reflectance, reflection, spd, specular, speed, terms)

GROUPS = [
    ("diffuse_specular", reflection),
    ("lambert", lambert),
    ("distance", distance),
    ("specular", specular),
    ("terms", terms),
    ("reflectance", reflectance),
    ("coloured_lights", colour),
    ("global", global_models),
    ("antialias", antialias),
    ("bounding", bounding),
    ("speed", speed),
    ("spd", spd),
    ("assignment", assignment),
]
