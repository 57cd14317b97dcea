"""No memory grows across 1,000 calls (resident set size from /proc)."""

import os

import pytest

import detach


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="needs /proc")
def test_no_leak_across_1000_calls():
    def calls(n):
        for _ in range(n):
            scene = detach.Scene.load("painleve-rod", mu="1.5")
            p = scene.pave(eps=1 / 16, method="natural")
            _ = p.leaves, p.areas
            try:
                detach.Scene.load("painleve-rod", mu="x")
            except ValueError:
                pass

    calls(100)
    before = rss_bytes()
    calls(1000)
    grown = rss_bytes() - before
    # One paving's leaves are a few kB: a leak of them per call would be
    # megabytes.
    assert grown < 2 * 1024 * 1024, f"RSS grew by {grown} bytes over 1000 calls"
