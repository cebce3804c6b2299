package io.dtron.selenium.sample;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;

/** Does nothing: input {@code i_ping} without variables, answered by {@code o_result(resCode)}. */
public final class Ping extends AbstractSeleniumAdapter {
    @Override
    protected void execute(IDtronChannelValued message) {
        // the automatic result is the whole point
    }
}
