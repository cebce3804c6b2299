package io.dtron.selenium.broken;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;

/** Input {@code i_overflow(user)}: the step dies of a virtual-machine error, as one out of memory would. */
@ChannelVariables("user")
public final class Overflow extends AbstractSeleniumAdapter {
    @Override
    protected void execute(IDtronChannelValued message) {
        throw new StackOverflowError("deliberate");
    }
}
