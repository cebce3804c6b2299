package io.dtron.bus.internal;

/**
 * Why a transport dropped a received message before anything read it: it lacked a valid code of the bus's secret
 * (security.md). A dropped message reaches no handler and changes no membership view.
 */
public enum DropReason {
    /**
     * No code, or not the code of the message (over JGroups: for its place in its connection): not made by a holder
     * of the bus's secret, or not for here.
     */
    UNAUTHENTICATED,
    /**
     * Sent again: over NATS, a message counter its sender already used, or none; over JGroups, a connection recorded
     * earlier (its hello was made for another connection).
     */
    REPLAYED,
    /** Its sender's time is too far from the time the bus stored it. */
    STALE
}
