package io.dtron.bus;

/**
 * Why a transport dropped a received message before anything read it: it lacked a valid code of the bus's secret
 * (security.md). A dropped message reaches no handler and changes no membership view.
 */
public enum DropReason {
    /** No code, or not the code of the message: not made by a holder of the bus's secret. */
    UNAUTHENTICATED,
    /** A message counter its sender already used (a message published again), or none. */
    REPLAYED,
    /** Its sender's time is too far from the time the bus stored it. */
    STALE
}
