"""Group masks (Yade's ``groupMask``): which bodies a collider pairs and which engines act on."""

import operator


def group_mask(value, who: str) -> int:
    """``value`` as a group mask (Yade's: a C int; negative values have every high bit set); an
    error naming ``who`` (the body or engine it is for) otherwise."""
    try:
        mask = operator.index(value)
    except TypeError:
        raise TypeError(f"mask of {who}: an integer is needed, got {value!r}") from None
    if not -2**31 <= mask < 2**31:
        raise OverflowError(f"mask of {who}: {mask} does not fit a 32-bit signed integer (Yade's groupMask)")
    return mask
