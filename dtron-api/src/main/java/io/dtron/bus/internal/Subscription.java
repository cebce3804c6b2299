package io.dtron.bus.internal;

/** A registration with a {@link Transport}; closing it ends the calls. Closing twice does nothing. */
@FunctionalInterface
public interface Subscription extends AutoCloseable {

    /** Stops calling the handler or listener of this subscription. */
    @Override
    void close();
}
