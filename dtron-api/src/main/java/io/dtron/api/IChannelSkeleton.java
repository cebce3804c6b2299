package io.dtron.api;

/** Anything that belongs to one bus channel. */
public interface IChannelSkeleton {

    /** Returns the channel name as on the bus: the model's channel without its {@code i_}/{@code o_} prefix. */
    String getChannelName();
}
