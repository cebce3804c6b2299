package io.dtron.models.streetlight;

import java.util.Arrays;
import java.util.List;

/**
 * The server's view of the light controllers: the state an operator requested for each, and the state and time
 * of its last report. Thread-safe.
 */
final class Controllers {
    private static final List<String> STREETS = List.of("Raekoja plats", "Rüütli", "Ülikooli", "Vabaduse",
            "Riia", "Narva maantee", "Turu", "Tähe", "Emajõe", "Kastani");

    /**
     * A controller's report.
     *
     * @param state the state it reported
     * @param nanos when it reported, in {@link System#nanoTime()}
     */
    record Report(LightState state, long nanos) {
    }

    private final LightState[] requested;
    private final Report[] reported;

    Controllers(int count) {
        requested = new LightState[count];
        Arrays.fill(requested, LightState.OFF);
        reported = new Report[count];
        Arrays.fill(reported, new Report(LightState.OFF, System.nanoTime()));
    }

    int count() {
        return requested.length;
    }

    /** Where controller {@code id} stands. */
    String place(int id) {
        return STREETS.get(id % STREETS.size()) + (id < STREETS.size() ? "" : " " + (id / STREETS.size() + 1));
    }

    /** Whether {@code id} names a controller. */
    boolean exists(int id) {
        return id >= 0 && id < requested.length;
    }

    synchronized void request(int id, LightState state) {
        requested[id] = state;
    }

    synchronized Report reported(int id) {
        return reported[id];
    }

    /** Records a report and returns the state requested of the controller. */
    synchronized LightState report(int id, LightState state) {
        reported[id] = new Report(state, System.nanoTime());
        return requested[id];
    }
}
