package io.dtron.model;

import io.dtron.xta.Pos;

/**
 * A channel or channel array: global, or local to one process. Channels are numbered from 0.
 *
 * @param name  the qualified name
 * @param type  {@link Type.Channel} or an array of channels
 * @param index the number of its first channel
 * @param owner the owning process's name, or null
 * @param pos   where it was declared
 */
public record ChannelVariable(String name, Type type, int index, String owner, Pos pos) {

    /** The name of channel number {@code channelIndex}, e.g. {@code appr[2]}. */
    public String elementName(int channelIndex) {
        return Names.element(name, type, channelIndex - index, Type::channels);
    }

    /** The kind of each channel of this variable. */
    public Type.Channel kind() {
        Type t = type;
        while (t instanceof Type.Array a) {
            t = a.element();
        }
        return (Type.Channel) t;
    }
}
