package io.dtron.selenium.duplicate;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;

/** An adapter with the simple name of the sample's {@link io.dtron.selenium.sample.Greet}, so the same channel. */
public final class Greet extends AbstractSeleniumAdapter {
    @Override
    protected void execute(IDtronChannelValued message) {
        throw new UnsupportedOperationException("never started");
    }
}
