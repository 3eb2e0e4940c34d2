"""``amiro har evaluate``'s confusion matrix in text: numbered rows and matching column headers."""

from __future__ import annotations

from amiro.evaluation.activity_evaluate import format_confusion


def test_every_column_has_a_header_over_its_counts() -> None:
    labels = ["drink_water", "standing_up", "falling", "unknown"]
    matrix = [[12, 0, 1, 0], [0, 1300, 0, 2], [0, 0, 9, 0], [1, 0, 0, 44]]
    title, header, *rows = format_confusion(labels, matrix)
    assert "rows: true" in title and "columns: predicted" in title
    assert header.split() == ["1", "2", "3", "4"]
    assert [r.split()[:2] for r in rows] == [[str(i), n] for i, n in enumerate(labels, 1)]
    for row, counts in zip(rows, matrix, strict=True):
        assert [int(v) for v in row.split()[2:]] == counts
        for k, count in enumerate(counts):  # each count ends under its column's number
            end = header.index(f" {k + 1}") + len(f" {k + 1}")
            assert row[:end].endswith(str(count))
