"""hertz/_ellipse_table.h is what tools/generate_ellipse_table.py writes.

Four pieces (both ends of the range, the first binade, the middle) are fitted again from
mpmath and compared with the committed header, value for value; the accuracy of the whole
table is tested through hertz.contact in tests/test_contact_exact.py.
"""

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEADER = ROOT / "hertz" / "_ellipse_table.h"
TOOLS = ROOT / "tools"


def committed_pieces():
    text = HEADER.read_text()
    body = text.split("ELLIPSE_TABLE[", 1)[1].split("= {", 1)[1]
    numbers = [float(x) for x in re.findall(r"[-+]?\d[\d.]*(?:e[-+]?\d+)?", body)]
    return numbers


@pytest.mark.skipif(not (TOOLS / "generate_ellipse_table.py").is_file(),
                    reason="tools/ is not beside the tests")
@pytest.mark.parametrize("piece", [0, 15, 517, 1023])
def test_header_matches_the_generator(piece):
    sys.path.insert(0, str(TOOLS))
    try:
        import generate_ellipse_table as gen
    finally:
        sys.path.remove(str(TOOLS))
    numbers = committed_pieces()
    stride = 3 * gen.TABLE_STRIDE
    assert len(numbers) == gen.TABLE_BINADES * 2**gen.TABLE_SPLIT_BITS * stride
    fitted = [v for row in gen.fit_piece(piece) for v in row]
    assert numbers[piece * stride:(piece + 1) * stride] == fitted
