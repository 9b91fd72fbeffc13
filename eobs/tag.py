"""e-obs tag generations and the nominal constants of the ADC-to-g formula (seed 003, sections 2, 3, 6).

Seed 003 section 6: ``a_i = (n_i - n_i,zerog) * c_i * g`` with n_i a raw 12-bit reading 0...4095,
n_i,zerog nominally 2048, and c_i (g per count)

* 0.001  high sensitivity, "only for Tags up to number 2241 possible",
* 0.0027 low sensitivity, tags up to number 2241,
* 0.0022 "for newer Tags with number greater than 2241" (fixed sensitivity: section 2 says the new
  sensor starts "with Tag id 2242").

Section 2 and the note under section 3: on the new sensor (tags from 2242) "the Y-axis now points to
the opposite direction, resulting correctly in a right-handed Cartesian coordinate system"; older
tags' Y points the other way. Section 3's six ideal readings (2048, 2048, 1593) ... are the new tags'
(2048 - 1/0.0022 = 1593.45 and 2048 + 1/0.0022 = 2502.55, rounded to 1593 and 2503).
"""

from __future__ import annotations

from flightmode.errors import SensorError, did_you_mean

ADC_MIN_COUNT = 0  # section 5.4 / 6: "digital readings between 0 and 4095"
ADC_MAX_COUNT = 4095
NOMINAL_ZERO_COUNT = 2048  # section 6: n_i,zerog "Nominal 2048"
LAST_OLD_TAG = (
    2241  # section 6: high/low sensitivity "only for Tags up to number 2241"; section 2: new from 2242
)
SLOPE_NEW_G_PER_COUNT = 0.0022  # section 6: tags numbered > 2241 (fixed sensitivity)
SLOPE_OLD_G_PER_COUNT = {"high": 0.001, "low": 0.0027}  # section 6: tags up to 2241, by the setting
AXES = "XYZ"


def check_tag_number(tag_number: int) -> int:
    """The tag number as an int >= 1 (e-obs tags are numbered from 1: section 7 'tags from number 1')."""
    if isinstance(tag_number, bool) or not isinstance(tag_number, int) or tag_number < 1:
        raise SensorError(f"e-obs tag number {tag_number!r}: must be an integer >= 1")
    return tag_number


def is_old_tag(tag_number: int) -> bool:
    """True for tags up to number 2241: the old sensor with high/low sensitivity and the reversed Y axis."""
    return check_tag_number(tag_number) <= LAST_OLD_TAG


def nominal_slope_g_per_count(tag_number: int, sensitivity: str | None = None) -> float:
    """Nominal c_i of section 6 for the tag. Old tags (<= 2241) need their sensitivity setting
    ('high' or 'low'); newer tags have one fixed sensitivity and take none."""
    if is_old_tag(tag_number):
        if sensitivity not in SLOPE_OLD_G_PER_COUNT:
            raise SensorError(
                f"e-obs tag {tag_number} (<= {LAST_OLD_TAG}) has a sensitivity setting: pass sensitivity "
                f"'high' (0.001 g/count) or 'low' (0.0027 g/count), got {sensitivity!r}"
                f"{did_you_mean(str(sensitivity), SLOPE_OLD_G_PER_COUNT)} (seed 003 section 6)"
            )
        return SLOPE_OLD_G_PER_COUNT[sensitivity]
    if sensitivity is not None:
        raise SensorError(
            f"e-obs tag {tag_number} (> {LAST_OLD_TAG}) has a fixed sensitivity (0.0022 g/count): "
            f"sensitivity must be None, got {sensitivity!r} (seed 003 sections 2, 6)"
        )
    return SLOPE_NEW_G_PER_COUNT


def y_sign(tag_number: int) -> int:
    """-1 for old tags, whose Y axis points opposite to the newer tags' right-handed frame; +1 otherwise."""
    return -1 if is_old_tag(tag_number) else 1


def tag_number_from_id(tag_id: str) -> int:
    """The tag number of a tag id that is one (the decoder's ``tag-serial-number``, section 5.4)."""
    if not (tag_id.isascii() and tag_id.isdigit()):
        raise SensorError(
            f"tag id {tag_id!r} is not an e-obs tag number (a Movebank individual id is not one): "
            f"pass tag_number= explicitly"
        )
    return check_tag_number(int(tag_id))
