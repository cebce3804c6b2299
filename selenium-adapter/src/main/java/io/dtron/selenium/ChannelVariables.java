package io.dtron.selenium;

import java.lang.annotation.Documented;
import java.lang.annotation.ElementType;
import java.lang.annotation.Retention;
import java.lang.annotation.RetentionPolicy;
import java.lang.annotation.Target;

/**
 * The variables attached to an adapter's input channel, as the model names them without the channel prefix:
 * {@code @ChannelVariables({"user", "controller"})} on class {@code Tick} for the model's {@code i_tick} with
 * globals {@code i_tick_user} and {@code i_tick_controller}. An adapter without it serves a channel without
 * variables.
 */
@Documented
@Retention(RetentionPolicy.RUNTIME)
@Target(ElementType.TYPE)
public @interface ChannelVariables {

    /** The variable names, in any order. */
    String[] value();
}
