package io.dtron.selenium.sample;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;

/** Requires {@link Greet}'s post-condition, then leaves the page: input {@code i_farewell(user)}. */
@ChannelVariables("user")
public final class Farewell extends AbstractSeleniumAdapter {
    @Inject
    Greet greet;

    /** Returns the greeting adapter Guice injected. */
    public Greet greet() {
        return greet;
    }

    @Override
    protected void execute(IDtronChannelValued message) {
        greet.requireGreeted();
        getWebDriver().navigate().to("about:blank");
    }
}
