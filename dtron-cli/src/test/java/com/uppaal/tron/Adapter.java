package com.uppaal.tron;

/**
 * The system under test's side of TRON's socket adapter, as in TRON's published Java API: {@link Reporter} calls
 * {@link #perform} for every input the tester sends. A test fixture written from the protocol's facts, so that the
 * tests run an adapter shaped like TRON's samples against {@code dtron tron}.
 */
public interface Adapter {
    /** Applies input {@code channel} (its id from {@link Reporter#getInputType}) with its variables' values. */
    void perform(int channel, int[] params);
}
